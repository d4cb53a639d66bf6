#!/usr/bin/env bash
# Makes sure the Rust toolchain that rust-toolchain.toml pins (with its clippy, rustfmt and
# wasm32 target) is installed. rustup does not download a pinned toolchain by itself where
# RUSTUP_AUTO_INSTALL=0: a `cargo` run before this would fail with "toolchain '…' is not
# installed".
set -euo pipefail
cd "$(dirname "$0")/.."
# Reads rust-toolchain.toml; quick when everything is there already.
channel=$(sed -n 's/^channel *= *"\(.*\)"/\1/p' rust-toolchain.toml)
if ! rustup toolchain list | grep -q "^$channel-"; then
    echo "Installing Rust $channel, which rust-toolchain.toml pins, with clippy, rustfmt and the wasm32 target (rustup, into ~/.rustup)." >&2
fi
rustup toolchain install >/dev/null
