#!/usr/bin/env bash
# Physics round on the device machine: builds rtrt from this tree and from .device/baseline side
# by side (no GPU tests), then plays the rigid-body scenes through `rtrt bench runtime` on 1 to 16
# threads (the baseline on every core), and bench frame on demo_physics at 1080p.
# Expects .device/ from tools/device/pack.sh (RTRT_BASELINE=...). RTRT_SKIP_BASELINE=1 runs this
# tree alone; RTRT_THREADS and RTRT_PHYSICS_FRAMES change the thread counts and frames.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/device_env.sh"
configure="-DCMAKE_PREFIX_PATH=$prefix -DRTRT_MODEL_DIR=$RTRT_MODEL_DIR -DRTRT_BUILD_TESTS=OFF"
[ -n "${RTRT_SKIP_BASELINE:-}" ] || (cd "$base" && cmake --preset gpu $configure >/dev/null && cmake --build --preset gpu -j 8 --target rtrt >/dev/null) > /tmp/base_build.log 2>&1 &
cmake --preset gpu $configure > /dev/null 2>&1
cmake --build --preset gpu -j 16 --target rtrt > $out/build.log 2>&1 || { grep -m20 -A5 error $out/build.log; exit 1; }
wait
r=build/gpu/game/rtrt; b=$base/build/gpu/game/rtrt; bc=$(cat $base/.commit)
lscpu | grep -E "Model name|^CPU\(s\)|Thread|MHz" | head -5
frames=${RTRT_PHYSICS_FRAMES:-600}
scenes="assets/scenes/bench_physics_10k.json assets/scenes/demo_physics.json"
echo "== this tree $RTRT_COMMIT"; $r bench runtime --frames $frames --threads ${RTRT_THREADS:-1,2,4,8,16} $scenes | tail -12
[ -n "${RTRT_SKIP_BASELINE:-}" ] || { echo "== baseline $bc"; $b bench runtime --frames $frames $scenes | tail -3; }
echo "== this tree $RTRT_COMMIT"; $r bench frame assets/scenes/demo_physics.json --size 1920x1080 -o $out/frame.json | tail -3
[ -n "${RTRT_SKIP_BASELINE:-}" ] || echo "== baseline $bc"; [ -n "${RTRT_SKIP_BASELINE:-}" ] || RTRT_COMMIT=$bc $b bench frame assets/scenes/demo_physics.json --size 1920x1080 -o $out/base-frame.json | tail -3
