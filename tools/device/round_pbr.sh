#!/usr/bin/env bash
# The PBR round on the device machine: build this tree (rtrt and its GPU test binary) and the baseline of
# .device/baseline (rtrt alone) side by side, run the GPU tests, then time demo_glass and
# demo_1000_instances at 1080p one after the other and the paper scene (dragon, teapot) on both, and
# bench materials on this tree. Expects .device/ from tools/device/pack.sh (RTRT_BASELINE=...).
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
r=build/gpu/game/rtrt; b=$base/build/gpu/game/rtrt
for i in 1; do
  echo "== this tree $RTRT_COMMIT"; $r bench frame assets/scenes/demo_glass.json assets/scenes/demo_1000_instances.json --size 1920x1080 -o $out/frame-$i.json | tail -2
  echo "== baseline $(cat $base/.commit)"; RTRT_COMMIT=$(cat $base/.commit) $b bench frame assets/scenes/demo_glass.json assets/scenes/demo_1000_instances.json --size 1920x1080 -o $out/base-frame-$i.json | tail -2
done
$r bench gpu --models dragon,teapot -o $out/gpu.json | tail -3
RTRT_COMMIT=$(cat $base/.commit) $b bench gpu --models dragon,teapot -o $out/base-gpu.json | tail -3
$r bench materials assets/models/pbr_showcase.gltf assets/models/textured_quads.gltf -o $out/materials.json
