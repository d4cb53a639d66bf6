#!/usr/bin/env bash
# Makes sure a Vulkan driver is installed. Where none is, installs Mesa's software driver
# (lavapipe, Debian's `mesa-vulkan-drivers`, with apt-get), which renders on the CPU: enough
# to run the examples and the GPU tests.
#
# With `--lavapipe` (the scripts that run the render tests), lavapipe itself: the render
# tests compare with the reference model within tolerances set on lavapipe, so they run on
# it (`WGPU_ADAPTER_NAME=llvmpipe`) even on a machine with a GPU, whose driver stays as it
# is; lavapipe is installed beside it where it is missing.
set -euo pipefail

lavapipe=false
if [[ ${1-} == --lavapipe ]]; then
    lavapipe=true
fi

# Whether a Vulkan driver's manifest matching "$1" (a glob) is installed.
has_driver() {
    local dir
    for dir in /usr/share/vulkan/icd.d /etc/vulkan/icd.d /usr/local/share/vulkan/icd.d; do
        if compgen -G "$dir/$1" >/dev/null; then
            return 0
        fi
    done
    return 1
}

# Whether the machine has a GPU device (Linux's render nodes, or NVIDIA's devices).
has_gpu() {
    compgen -G "/dev/dri/renderD*" >/dev/null || compgen -G "/dev/nvidia[0-9]*" >/dev/null
}

if $lavapipe; then
    pattern="lvp_icd*.json"
    if has_gpu; then
        echo "Note: the render tests run on Mesa's lavapipe (WGPU_ADAPTER_NAME=llvmpipe), not on this machine's GPU: their tolerances are set on lavapipe." >&2
    fi
else
    pattern="*.json"
fi
if has_driver "$pattern"; then
    exit 0
fi

echo "Installing Mesa's lavapipe, a Vulkan driver that renders on the CPU (apt-get install mesa-vulkan-drivers)." >&2
if ! command -v apt-get >/dev/null; then
    echo "error: install Mesa's lavapipe (or, for the examples, a Vulkan driver for your GPU), and run again." >&2
    exit 1
fi
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
    sudo_cmd=(sudo)
fi
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq mesa-vulkan-drivers >/dev/null
has_driver "$pattern" || { echo "error: mesa-vulkan-drivers installed no Vulkan driver" >&2; exit 1; }
