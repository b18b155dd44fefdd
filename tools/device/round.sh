#!/usr/bin/env bash
# One GPU round on the device machine: build for sm_90 without OpenImageIO, run the GPU tests
# (ctest -L gpu), render the verification scenes on the GPU, and leave logs, JSON and images in
# $OUT. Expects .device/ from tools/device/pack.sh. With .device/baseline (pack.sh's
# RTRT_BASELINE), the earlier commit is built too and benchmarked (gpu, grid, frame) right after
# this tree, on the same machine: baseline.tar holds its JSON, bench.log both tables.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
out=${OUT:-$root/build/device-out}
mkdir -p "$out"
prefix=$root/.device/prefix/usr
export LD_LIBRARY_PATH=$prefix/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
export RTRT_MODEL_DIR=$root/.device/models
export PATH=/usr/local/cuda/bin:$PATH
# The tree there has no .git: the commit comes from .device/commit (see tools/device/pack.sh).
export RTRT_COMMIT=$(cat "$root/.device/commit" 2>/dev/null || echo unknown)
{
    nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv
    echo "commit $RTRT_COMMIT"
} | tee "$out/device.txt"
cmake --preset gpu -DCMAKE_PREFIX_PATH="$prefix" -DRTRT_MODEL_DIR="$RTRT_MODEL_DIR" \
    >"$out/configure.log" 2>&1 || { tail -40 "$out/configure.log"; exit 1; }
cmake --build --preset gpu -j 16 >"$out/build.log" 2>&1 || { grep -m20 -A5 error "$out/build.log"; exit 1; }
ctest --test-dir build/gpu -L gpu --output-on-failure -j 1 2>&1 | tee "$out/gpu_tests.log" | tail -25
rtrt=build/gpu/game/rtrt
# At most 8 files come back from $OUT: renders travel as one tar, the benchmarks' JSON as another
# (results.tar), their tables as one log.
renders=$(mktemp -d)
for scene in dragon reflective_sphere refractive_sphere teapot_shadow; do
    "$rtrt" render "assets/scenes/$scene.json" --backend cuda -o "$renders/$scene.ppm" --size 640x360
done 2>&1 | tee "$renders/renders.log"
"$rtrt" render assets/models/pbr_showcase.gltf --backend cuda -o "$renders/pbr_showcase.ppm" \
    --size 960x540 2>&1 | tee -a "$renders/renders.log"
tar -C "$renders" -cf "$out/renders.tar" .
results=$(mktemp -d)
{
    "$rtrt" bench gpu -o "$results/gpu-bench.json"
    "$rtrt" bench grid -o "$results/grid-bench.json"
    "$rtrt" bench frame assets/scenes/demo_1000_instances.json assets/scenes/demo_physics.json \
        assets/scenes/demo_glass.json -o "$results/frame-bench.json"
    "$rtrt" bench frame assets/scenes/demo_1000_instances.json assets/scenes/demo_physics.json \
        assets/scenes/demo_glass.json --size 1920x1080 -o "$results/frame-bench-1080p.json"
    # ~10 s of GPU time; the double reference renders on the host's CPU (docs/accuracy.md).
    "$rtrt" bench accuracy --backend cuda -o "$results/accuracy-gpu.json"
    "$rtrt" bench materials assets/models/pbr_showcase.gltf assets/models/textured_quads.gltf \
        -o "$results/materials-bench.json"
} 2>&1 | tee "$out/bench.log"
tar -C "$results" -cf "$out/results.tar" .
# RTRT_SANITIZE=1: the whole GPU suite under compute-sanitizer's memcheck and racecheck.
if [ "${RTRT_SANITIZE:-0}" = 1 ]; then
    for tool in memcheck racecheck; do
        echo "== compute-sanitizer --tool $tool build/gpu/tests/rtrt_gpu_tests"
        compute-sanitizer --tool "$tool" --error-exitcode 3 build/gpu/tests/rtrt_gpu_tests 2>&1 |
            grep -E "ERROR SUMMARY|RACECHECK SUMMARY|Hazard|Invalid|PASSED|FAILED|tests ran"
        echo "exit ${PIPESTATUS[0]}"
    done 2>&1 | tee "$out/sanitizer.log"
fi
base=$root/.device/baseline
if [ -d "$base" ]; then
    echo "== baseline $(cat "$base/.commit")" | tee -a "$out/bench.log"
    (cd "$base" && cmake --preset gpu -DCMAKE_PREFIX_PATH="$prefix" -DRTRT_MODEL_DIR="$RTRT_MODEL_DIR" \
        -DRTRT_BUILD_TESTS=OFF >/dev/null && cmake --build --preset gpu -j 16 --target rtrt >/dev/null) ||
        echo "baseline build failed" | tee -a "$out/bench.log"
    bdir=$(mktemp -d)
    export RTRT_COMMIT=$(cat "$base/.commit")
    {
        "$base/build/gpu/game/rtrt" bench gpu -o "$bdir/baseline-gpu-bench.json"
        "$base/build/gpu/game/rtrt" bench grid -o "$bdir/baseline-grid-bench.json"
        "$base/build/gpu/game/rtrt" bench frame assets/scenes/demo_1000_instances.json \
            assets/scenes/demo_physics.json assets/scenes/demo_glass.json \
            -o "$bdir/baseline-frame-bench.json"
        "$base/build/gpu/game/rtrt" bench frame assets/scenes/demo_1000_instances.json \
            assets/scenes/demo_physics.json assets/scenes/demo_glass.json --size 1920x1080 \
            -o "$bdir/baseline-frame-bench-1080p.json"
    } 2>&1 | tee -a "$out/bench.log"
    tar -C "$bdir" -cf "$out/baseline.tar" .
fi
if [ "${RTRT_DEVICE_EXTRA:-}" != "" ]; then eval "$RTRT_DEVICE_EXTRA" 2>&1 | tee -a "$out/bench.log"; fi
rm -f "$out/configure.log" "$out/build.log"
