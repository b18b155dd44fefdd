#!/usr/bin/env bash
# Physics round on the device machine: builds rtrt from this tree and from .device/baseline side
# by side, then plays the rigid-body scenes through `rtrt bench runtime` on 1 to 16 threads (the
# baseline on every core; since 2026-12-05 a world of fewer than 1,024 rigid bodies, such as
# demo_physics, steps on one thread whatever the count), and bench frame on demo_physics at 1080p,
# this tree and the baseline one after the other.
# Expects .device/ from tools/device/pack.sh (RTRT_BASELINE=...). RTRT_SKIP_BASELINE=1 runs this
# tree alone; RTRT_THREADS and RTRT_PHYSICS_FRAMES change the thread counts and frames;
# RTRT_SOLVERS (default cpu; e.g. cpu,gpu) the contact solvers; RTRT_ROUNDS (default 1) repeats
# the runtime comparison, alternating; RTRT_GPU_TESTS=1 also builds and runs the GPU tests.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/device_env.sh"
configure="-DCMAKE_PREFIX_PATH=$prefix -DRTRT_MODEL_DIR=$RTRT_MODEL_DIR"
targets=rtrt
if [ "${RTRT_GPU_TESTS:-0}" = 1 ]; then targets="rtrt rtrt_gpu_tests"; else configure="$configure -DRTRT_BUILD_TESTS=OFF"; fi
[ -n "${RTRT_SKIP_BASELINE:-}" ] || (cd "$base" && cmake --preset gpu $configure -DRTRT_BUILD_TESTS=OFF >/dev/null && cmake --build --preset gpu -j 8 --target rtrt >/dev/null) > /tmp/base_build.log 2>&1 &
cmake --preset gpu $configure > /dev/null 2>&1
cmake --build --preset gpu -j 16 --target $targets > $out/build.log 2>&1 || { grep -m20 -A5 error $out/build.log; exit 1; }
wait
[ "${RTRT_GPU_TESTS:-0}" = 1 ] && build/gpu/tests/rtrt_gpu_tests 2>&1 | grep -E "FAILED|PASSED|tests ran" | tail -8
r=build/gpu/game/rtrt; b=$base/build/gpu/game/rtrt; bc=$(cat $base/.commit)
lscpu | grep -E "Model name|^CPU\(s\)|Thread|MHz" | head -5
frames=${RTRT_PHYSICS_FRAMES:-600}
solvers=${RTRT_SOLVERS:-cpu}
scenes="assets/scenes/bench_physics_10k.json assets/scenes/demo_physics.json"
rows=$(( 2 * ${#solvers} ))
for round in $(seq ${RTRT_ROUNDS:-1}); do
    echo "== round $round: this tree $RTRT_COMMIT"; $r bench runtime --frames $frames --threads ${RTRT_THREADS:-1,2,4,8,16} --physics-solver $solvers $scenes | tail -12
    [ -n "${RTRT_SKIP_BASELINE:-}" ] || { echo "== round $round: baseline $bc"; $b bench runtime --frames $frames --physics-solver $solvers $scenes | tail -4; }
done
for solver in ${solvers//,/ }; do
    echo "== this tree $RTRT_COMMIT, $solver solver"; $r bench frame assets/scenes/demo_physics.json --size 1920x1080 --physics-solver $solver -o $out/frame-$solver.json | tail -1
    [ -n "${RTRT_SKIP_BASELINE:-}" ] || { echo "== baseline $bc, $solver solver"; RTRT_COMMIT=$bc $b bench frame assets/scenes/demo_physics.json --size 1920x1080 --physics-solver $solver -o $out/base-frame-$solver.json | tail -1; }
done
