#!/usr/bin/env bash
# Makes sure what the browser tests need is installed: Chromium and Node.js (Debian's
# packages; Node.js 20 or newer, which playwright-core needs) and, into
# target/browser/node_modules, playwright-core (which drives Chromium) and three (three.js,
# whose own render of tests/three_js/scene.json scripts/three/render.cjs makes). Installs only
# what is missing or at another version; quick when all is there.
set -euo pipefail
cd "$(dirname "$0")/.."

out=target/browser
playwright_version=1.65.1
three_version=0.187.0

# apt-get as root, or through sudo.
apt_install() {
    if ! command -v apt-get >/dev/null; then
        echo "error: install $* (no apt-get here), and run again." >&2
        exit 1
    fi
    local sudo_cmd=()
    if [ "$(id -u)" -ne 0 ]; then
        sudo_cmd=(sudo)
    fi
    "${sudo_cmd[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq "$@" >/dev/null
}

if [[ ! -x /usr/bin/chromium ]]; then
    echo "Installing Chromium, for the render test that compares with three.js's picture (apt-get install chromium)." >&2
    apt_install chromium
fi
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
    echo "Installing Node.js and npm, which run three.js in Chromium (apt-get install nodejs npm)." >&2
    apt_install nodejs npm
fi
node_major=$(node -p 'process.versions.node.split(".")[0]')
if ((node_major < 20)); then
    echo "error: Node.js $(node --version) is too old for playwright-core $playwright_version; install Node.js 20 or newer." >&2
    exit 1
fi

# has NAME VERSION: whether NAME is installed in $out/node_modules at VERSION.
has() {
    [[ -f $out/node_modules/$1/package.json ]] &&
        [[ $(node -p "require('./$out/node_modules/$1/package.json').version") == "$2" ]]
}
# Both in one command: an `npm install --no-save` removes the packages that an earlier one
# installed with --no-save, so installing only the missing one would lose the other.
if ! has playwright-core "$playwright_version" || ! has three "$three_version"; then
    echo "Installing playwright-core@$playwright_version and three@$three_version into $out/node_modules (npm install)." >&2
    mkdir -p "$out"
    npm install --prefix "$out" --no-save --no-audit --no-fund --loglevel=error \
        "playwright-core@$playwright_version" "three@$three_version"
fi
has playwright-core "$playwright_version" || { echo "error: playwright-core@$playwright_version is not installed in $out" >&2; exit 1; }
has three "$three_version" || { echo "error: three@$three_version is not installed in $out" >&2; exit 1; }
