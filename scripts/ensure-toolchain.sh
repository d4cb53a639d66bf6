#!/usr/bin/env bash
# Makes sure the Rust toolchain that rust-toolchain.toml pins (with its clippy, rustfmt and
# wasm32 target) is installed. rustup does not download a pinned toolchain by itself where
# RUSTUP_AUTO_INSTALL=0: a `cargo` run before this would fail with "toolchain '…' is not
# installed".
set -euo pipefail
cd "$(dirname "$0")/.."
# Reads rust-toolchain.toml; quick when everything is there already.
rustup toolchain install >/dev/null
