#!/usr/bin/env bash
# Runs the showcase example: in a window where a display exists, else it renders
# target/showcase.png. Installs a Vulkan driver first if there is none.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/ensure-toolchain.sh
scripts/ensure-vulkan.sh
source scripts/software-adapter.sh
source scripts/runtime-dir.sh
# Not `exec`: the private runtime directory is removed when this script exits.
cargo run --example showcase -- "$@"
