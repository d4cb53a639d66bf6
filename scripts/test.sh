#!/usr/bin/env bash
# Runs every test: unit tests, the headless render tests (on the Vulkan device; Mesa's
# lavapipe where there is no GPU), the doc tests, and each example rendered headless and
# compared with the reference model; then the render tests and the examples again under
# WebGL2's limits. Installs a Vulkan driver first if there is none. The render tests compare
# against the reference model with tolerances set on lavapipe, so they always run on it.
#
# The work runs two at a time where it can, one per core: the tests one per process with
# cargo-nextest (where it is installed; `cargo test` otherwise), the examples two at a time.
# The soak test, which measures its own CPU time, runs alone.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/ensure-toolchain.sh
scripts/ensure-vulkan.sh --lavapipe
# Chromium, Node.js and three.js, for the render test that compares with three.js's picture.
scripts/ensure-browser.sh
source scripts/runtime-dir.sh
export WGPU_ADAPTER_NAME="${WGPU_ADAPTER_NAME:-llvmpipe}"
# Each part says when it starts, in seconds since the script began; the script ends with
# each part's seconds.
STEP_PREFIX="== test.sh"
source scripts/steps.sh
part() { step "$@"; }

# The examples rendered and compared below (the minimal one is rendered by the GPU tests:
# it opens a window and nothing else).
EXAMPLES="showcase searchlight orbiting_light many_lights textured_cubes gltf_scene baked_room toon area_lights"

# Runs the test targets named by "$@", each test in its own process and two at a time where
# cargo-nextest is installed, else with `cargo test` (each binary's tests on two threads).
run_tests() {
    if command -v cargo-nextest >/dev/null; then
        cargo nextest run --no-fail-fast "$@"
    else
        cargo test "$@"
    fi
}

# Every example must still render: each writes its PNG headless into the folder "$1", then,
# in the same run, compares its scene with the reference model, pixel by pixel (what the
# comparison leaves out and why: examples/support/compare.rs), and exits; two at a time.
render_examples() {
    local folder="$1"
    # Built first, so that the runs below only run.
    cargo build --quiet --examples
    printf '%s\n' $EXAMPLES | xargs -P 2 -I{} \
        cargo run --quiet --example {} -- --headless "$folder/{}.png" --compare
}

part "every target's tests, on the device's own limits"
# The library's unit tests, the fuzz cases, the render tests and the shader tier.
run_tests --lib --test fuzz --test gpu --test shader_modules "$@"
# The soak test measures its process's CPU time: alone.
cargo test --test soak "$@"
# The doc tests, the benchmark once and the `bench` example's tests; the other examples are
# built as `cargo run --example` below runs them (not twice, as test harnesses too).
cargo test --doc "$@"
cargo test --benches --examples "$@"
# The glTF test asset is what its writer writes (a workspace crate without Bevy).
cargo test -p phong_gltf_asset "$@"

part "the examples, and the benchmark beside them"
# The benchmark still runs (a small scene, a few frames): its figures are not judged here,
# so it runs beside the examples.
cargo run --quiet --example bench -- --quick >target/bench-quick.log 2>&1 &
bench=$!
render_examples target/examples
# The showcase's sphere shows its three highlights where the lighting model puts them.
cargo run --quiet --example showcase -- --check target/examples/showcase.png
# A scene file rendered to PNG and OpenEXR, as the README shows.
cargo run --quiet --example render_scene -- assets/scenes/shapes.phong_scene.ron \
    --out target/examples/render_scene --size 480x270 --check
cargo run --quiet --example render_scene -- assets/scenes/shadows.phong_scene.ron \
    --out target/examples/render_scene_shadows --size 480x270
cargo run --quiet --example render_scene -- --help >/dev/null
if ! wait "$bench"; then
    cat target/bench-quick.log
    echo "the benchmark failed (its output is above)" >&2
    exit 1
fi
tail -n 3 target/bench-quick.log

# Again under WebGL2's limits (no storage buffers: the scene data travels in a texture):
# the render tests with the same tolerances, and every example.
export WGPU_SETTINGS_PRIO=webgl2
part "the render tests and the examples under WebGL2's limits"
run_tests --test gpu "$@"
cargo test --test soak "$@"
render_examples target/examples/webgl2
cargo run --quiet --example showcase -- --check target/examples/webgl2/showcase.png
cargo run --quiet --example render_scene -- assets/scenes/shadows.phong_scene.ron \
    --out target/examples/webgl2/render_scene_shadows --size 480x270
cargo run --quiet --example render_scene -- assets/scenes/shapes.phong_scene.ron \
    --out target/examples/webgl2/render_scene --size 480x270 --check
steps_summary
