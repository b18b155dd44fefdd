#!/usr/bin/env bash
# A/B round on the device machine: build this tree (rtrt and its GPU tests) and the baseline of
# .device/baseline (rtrt alone) side by side, run the GPU tests, then bench gpu on every paper
# model and bench frame on the 1080p demos, this tree and the baseline one after the other.
# Expects .device/ from tools/device/pack.sh (RTRT_BASELINE=...).
set -uo pipefail
root=$(pwd); out=$OUT
prefix=$root/.device/prefix/usr
export LD_LIBRARY_PATH=$prefix/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
export RTRT_MODEL_DIR=$root/.device/models PATH=/usr/local/cuda/bin:$PATH
export RTRT_COMMIT=$(cat .device/commit)
base=$root/.device/baseline
(cd "$base" && cmake --preset gpu -DCMAKE_PREFIX_PATH="$prefix" -DRTRT_MODEL_DIR="$RTRT_MODEL_DIR" -DRTRT_BUILD_TESTS=OFF >/dev/null && cmake --build --preset gpu -j 8 --target rtrt >/dev/null) > /tmp/base_build.log 2>&1 &
cmake --preset gpu -DCMAKE_PREFIX_PATH="$prefix" -DRTRT_MODEL_DIR="$RTRT_MODEL_DIR" > /dev/null 2>&1
cmake --build --preset gpu -j 16 --target rtrt rtrt_gpu_tests > $out/build.log 2>&1 || { grep -m20 -A5 error $out/build.log; exit 1; }
wait
build/gpu/tests/rtrt_gpu_tests 2>&1 | grep -E "FAILED|PASSED|tests ran" | tail -8
r=build/gpu/game/rtrt; b=$base/build/gpu/game/rtrt; bc=$(cat $base/.commit)
echo "== this tree $RTRT_COMMIT"; $r bench gpu -o $out/gpu.json | tail -9
echo "== baseline $bc"; RTRT_COMMIT=$bc $b bench gpu -o $out/base-gpu.json | tail -9
scenes="assets/scenes/demo_glass.json assets/scenes/demo_1000_instances.json assets/scenes/demo_crowd.json"
echo "== this tree $RTRT_COMMIT"; $r bench frame $scenes --size 1920x1080 -o $out/frame.json | tail -4
echo "== baseline $bc"; RTRT_COMMIT=$bc $b bench frame $scenes --size 1920x1080 -o $out/base-frame.json | tail -4
