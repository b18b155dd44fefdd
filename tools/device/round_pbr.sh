#!/usr/bin/env bash
# The PBR round on the device machine: build this tree (rtrt and its GPU test binary) and the baseline of
# .device/baseline (rtrt alone) side by side, run the GPU tests, then time demo_glass and
# demo_1000_instances at 1080p one after the other and the paper scene (dragon, teapot) on both, and
# bench materials on this tree. Expects .device/ from tools/device/pack.sh (RTRT_BASELINE=...).
set -uo pipefail
source "$(dirname "$0")/ab_build.sh"
for i in 1; do
  echo "== this tree $RTRT_COMMIT"; $r bench frame assets/scenes/demo_glass.json assets/scenes/demo_1000_instances.json --size 1920x1080 -o $out/frame-$i.json | tail -2
  echo "== baseline $(cat $base/.commit)"; RTRT_COMMIT=$(cat $base/.commit) $b bench frame assets/scenes/demo_glass.json assets/scenes/demo_1000_instances.json --size 1920x1080 -o $out/base-frame-$i.json | tail -2
done
$r bench gpu --models dragon,teapot -o $out/gpu.json | tail -3
RTRT_COMMIT=$(cat $base/.commit) $b bench gpu --models dragon,teapot -o $out/base-gpu.json | tail -3
$r bench materials assets/models/pbr_showcase.gltf assets/models/textured_quads.gltf -o $out/materials.json
