# Sourced by the A/B rounds (round_pbr.sh, round_gpu_ab.sh) on the device machine: builds this
# tree (rtrt and its GPU tests) and the baseline of .device/baseline (rtrt alone) side by side,
# runs the GPU tests, and sets r and b (the two rtrt binaries) and bc (the baseline's commit).
# Expects .device/ from tools/device/pack.sh (RTRT_BASELINE=...) and $OUT.
source "$(dirname "${BASH_SOURCE[0]}")/device_env.sh"
(cd "$base" && cmake --preset gpu -DCMAKE_PREFIX_PATH="$prefix" -DRTRT_MODEL_DIR="$RTRT_MODEL_DIR" -DRTRT_BUILD_TESTS=OFF >/dev/null && cmake --build --preset gpu -j 8 --target rtrt >/dev/null) > /tmp/base_build.log 2>&1 &
cmake --preset gpu -DCMAKE_PREFIX_PATH="$prefix" -DRTRT_MODEL_DIR="$RTRT_MODEL_DIR" > /dev/null 2>&1
cmake --build --preset gpu -j 16 --target rtrt rtrt_gpu_tests > $out/build.log 2>&1 || { grep -m20 -A5 error $out/build.log; exit 1; }
wait
build/gpu/tests/rtrt_gpu_tests 2>&1 | grep -E "FAILED|PASSED|tests ran" | tail -8
r=build/gpu/game/rtrt; b=$base/build/gpu/game/rtrt; bc=$(cat $base/.commit)
