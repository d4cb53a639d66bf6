#!/usr/bin/env bash
# Runs the showcase example: in a window where a display exists, else it renders
# target/showcase.png. Installs a Vulkan driver first if there is none.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/ensure-vulkan.sh
source scripts/software-adapter.sh
exec cargo run --example showcase -- "$@"
