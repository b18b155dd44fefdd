#!/usr/bin/env bash
# A/B round in one binary: builds this tree (rtrt and its GPU tests) and runs the benchmarks with
# the environment variable $AB_VAR unset (A) and set to 1 (B), alternating, so that both halves
# share a machine, a build and a warm GPU; renders compare the two images byte for byte.
# Expects .device/ from tools/device/pack.sh; AB_VAR names the switch.
set -uo pipefail
source "$(dirname "$0")/device_env.sh"
var=${AB_VAR:?AB_VAR names the switch}
start=$(date +%s)
cmake --preset gpu -DCMAKE_PREFIX_PATH="$prefix" -DRTRT_MODEL_DIR="$RTRT_MODEL_DIR" > /dev/null 2>&1
cmake --build --preset gpu -j 16 --target rtrt ${AB_TARGETS:-} > $out/build.log 2>&1 || { grep -m20 -A5 error $out/build.log; exit 1; }
echo "built in $(( $(date +%s) - start )) s"
r=build/gpu/game/rtrt
img=$(mktemp -d)
for scene in dragon reflective_sphere refractive_sphere teapot_shadow demo_1000_instances demo_glass; do
    env -u $var $r render assets/scenes/$scene.json --backend cuda -o $img/a.ppm --size 640x360 > /dev/null 2>&1
    env $var=1 $r render assets/scenes/$scene.json --backend cuda -o $img/b.ppm --size 640x360 > /dev/null 2>&1
    cmp -s $img/a.ppm $img/b.ppm && echo "$scene: same bytes" || echo "$scene: DIFFERENT ($(cmp -l $img/a.ppm $img/b.ppm | wc -l) bytes)"
done
for round in 1 2; do
    echo "== gpu round $round A"; env -u $var $r bench gpu --frames ${AB_FRAMES:-200} -o $out/gpu-a$round.json | tail -7
    echo "== gpu round $round B"; env $var=1 $r bench gpu --frames ${AB_FRAMES:-200} -o $out/gpu-b$round.json | tail -7
done
for round in 1 2; do
    echo "== grid round $round A"; env -u $var $r bench grid --counts ${AB_GRID:-1000,10000,100000} -o $out/grid-a$round.json | tail -4
    echo "== grid round $round B"; env $var=1 $r bench grid --counts ${AB_GRID:-1000,10000,100000} -o $out/grid-b$round.json | tail -4
done
scenes="assets/scenes/demo_glass.json assets/scenes/demo_1000_instances.json assets/scenes/demo_physics.json"
echo "== frame A"; env -u $var $r bench frame $scenes --size 1920x1080 -o $out/frame-a.json | tail -4
echo "== frame B"; env $var=1 $r bench frame $scenes --size 1920x1080 -o $out/frame-b.json | tail -4
echo "total $(( $(date +%s) - start )) s"
