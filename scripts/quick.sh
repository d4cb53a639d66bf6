#!/usr/bin/env bash
# The quick loop, for after every change (about two minutes once built): the library's
# unit tests, the shader modules composed and validated with each of their defs on and off
# (not every material variant: scripts/test.sh composes those), and one render on the
# device, the minimal example against the reference model. scripts/test.sh runs everything.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/ensure-toolchain.sh
scripts/ensure-vulkan.sh --lavapipe
source scripts/runtime-dir.sh
export WGPU_ADAPTER_NAME="${WGPU_ADAPTER_NAME:-llvmpipe}"
STEP_PREFIX="== quick.sh"
source scripts/steps.sh

step "the library's unit tests"
cargo test --quiet --lib
step "the shader modules, each def on and off, and their layouts"
cargo test --quiet --test shader_modules -- \
    --skip every_phong_material_variant_validates \
    --skip every_phong_prepass_variant_validates
step "one render: the minimal example against the reference model"
cargo test --quiet --test gpu -- adoption::the_minimal_example
steps_summary
