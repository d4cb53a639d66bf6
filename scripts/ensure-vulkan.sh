#!/usr/bin/env bash
# Makes sure a Vulkan driver is installed. Where none is, installs Mesa's software driver
# (lavapipe), which renders on the CPU: enough to run the examples and the GPU tests.
set -euo pipefail

has_vulkan_driver() {
    local dir
    for dir in /usr/share/vulkan/icd.d /etc/vulkan/icd.d /usr/local/share/vulkan/icd.d; do
        if compgen -G "$dir/*.json" >/dev/null; then
            return 0
        fi
    done
    return 1
}

if has_vulkan_driver; then
    exit 0
fi

echo "No Vulkan driver found: installing Mesa's lavapipe (mesa-vulkan-drivers)." >&2
if ! command -v apt-get >/dev/null; then
    echo "error: install a Vulkan driver for your GPU, or Mesa's lavapipe, and run again." >&2
    exit 1
fi
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
    sudo_cmd=(sudo)
fi
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq mesa-vulkan-drivers >/dev/null
has_vulkan_driver || { echo "error: mesa-vulkan-drivers installed no Vulkan driver" >&2; exit 1; }
