#!/usr/bin/env bash
# Checks by hand that the crate publishes: the files the package holds (`cargo package
# --list`), then `cargo publish --dry-run`, which packs the crate, builds it alone from the
# package (its verification build, in target/package) and stops before uploading; then the
# package's one example, built from the unpacked package. Not part of CI: the verification
# builds Bevy again with the library's own features (about 20 minutes here). Pass
# `--allow-dirty` to check a checkout with uncommitted changes.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/ensure-toolchain.sh

echo "== the files of the package"
cargo package --list -p bevy_phong "$@"
echo "== cargo publish --dry-run"
cargo publish --dry-run -p bevy_phong "$@"
echo "== the package's example, built from the package"
version=$(cargo metadata --no-deps --format-version 1 |
    python3 -c 'import json,sys; print(next(p["version"] for p in json.load(sys.stdin)["packages"] if p["name"] == "bevy_phong"))')
cargo build --manifest-path "target/package/bevy_phong-$version/Cargo.toml" \
    --target-dir target/package/target --example minimal
echo "package check passed"
