#!/usr/bin/env bash
# The showcase in a browser (WebGL2). Builds the showcase for wasm32, binds it with
# wasm-bindgen into target/browser/site and serves that on localhost, then:
#   scripts/browser.sh          opens it in headless Chromium, waits until the app has drawn,
#                               screenshots the canvas to target/browser/showcase.png and
#                               checks the sphere's three highlights on it (`--check`);
#   scripts/browser.sh --serve  keeps serving it and prints the address to open.
# Installs what is missing: the pinned toolchain and its wasm32 target, wasm-bindgen-cli at
# the version in Cargo.lock and, for the test, what scripts/ensure-browser.sh installs
# (Chromium and Node.js, and playwright-core and three.js in target/browser/node_modules).
set -euo pipefail
cd "$(dirname "$0")/.."

mode=test
case "${1:-}" in
    "") ;;
    --serve) mode=serve ;;
    *) echo "usage: scripts/browser.sh [--serve]" >&2; exit 2 ;;
esac

out=target/browser
site=$out/site
fail() {
    echo "browser test failed: $*" >&2
    exit 1
}

# What the build and the test need: the pinned toolchain with its wasm32 target.
scripts/ensure-toolchain.sh
bindgen_version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/[^0-9.]/, ""); print; exit }' Cargo.lock)
[[ -n $bindgen_version ]] || fail "no wasm-bindgen in Cargo.lock"
if [[ $(wasm-bindgen --version 2>/dev/null) != "wasm-bindgen $bindgen_version" ]]; then
    # Not --locked: the lock file it ships names a webpki-roots release that the registry
    # here does not serve.
    cargo install wasm-bindgen-cli --version "$bindgen_version"
fi
if [[ $mode == test ]]; then
    scripts/ensure-browser.sh
fi

# The page: the wasm module, its JavaScript bindings and index.html. The showcase needs no
# glTF, so the crate's default `gltf` feature is left out of the browser build, which uses
# the `web` profile (Cargo.toml: dependencies optimized at level 1).
cargo build --profile web --target wasm32-unknown-unknown --no-default-features --example showcase
rm -rf "$site"
wasm-bindgen --target web --no-typescript --out-dir "$site" --out-name showcase \
    target/wasm32-unknown-unknown/web/examples/showcase.wasm
cp examples/showcase/index.html "$site/"

# Serve it on the loopback address: for a person on port 8080, for the test on a free port
# (BROWSER_PORT chooses another).
if [[ $mode == serve ]]; then
    port=${BROWSER_PORT:-8080}
else
    port=${BROWSER_PORT:-$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')}
fi
url="http://127.0.0.1:$port/"
if [[ $mode == serve ]]; then
    echo "serving the showcase at $url (Ctrl-C stops)"
    exec python3 -m http.server "$port" --bind 127.0.0.1 --directory "$site"
fi
python3 -m http.server "$port" --bind 127.0.0.1 --directory "$site" >"$out/server.log" 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null || true' EXIT
answers() { python3 -c 'import sys, urllib.request; urllib.request.urlopen(sys.argv[1], timeout=1)' "$url" 2>/dev/null; }
for _ in $(seq 50); do
    answers && break
    sleep 0.2
done
answers || fail "the page server did not answer at $url (see $out/server.log)"

rm -f "$out/showcase.png"
node scripts/browser/screenshot.cjs "$url" "$out/showcase.png" "$out/node_modules" ||
    fail "no screenshot of the showcase (see the lines above)"
cargo run --quiet --example showcase -- --check "$out/showcase.png" ||
    fail "the screenshot $out/showcase.png lacks a highlight"
echo "browser test passed: $out/showcase.png"
