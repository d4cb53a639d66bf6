# Sourced by the other scripts: on a machine without a GPU (no /dev/dri render node), ask
# wgpu for Mesa's software Vulkan driver by name.
if [ -z "${WGPU_ADAPTER_NAME:-}" ] && ! compgen -G "/dev/dri/renderD*" >/dev/null; then
    export WGPU_ADAPTER_NAME=llvmpipe
fi
