#!/usr/bin/env bash
# Variants of the tracer measured side by side on the device machine: this tree and every folder
# of .device/variants/ (pack.sh --variant <commit>) are built at once (rtrt alone; this tree also
# its GPU tests, which run first), then bench gpu, bench grid and bench frame run for each build
# in turn, RTRT_ROUNDS times (default 2) interleaved, so that a drift of the machine shows as a
# spread between rounds rather than as a difference between variants. RTRT_GRID=0 leaves out
# bench grid, RTRT_FRAME=0 bench frame. Leaves results.tar (the JSON of every run) and
# variants.log in $OUT.
set -uo pipefail
source "$(dirname "$0")/device_env.sh"
builds=("$root")
for v in "$root"/.device/variants/*/; do [ -d "$v" ] && builds+=("${v%/}"); done
jobs=$((16 / ${#builds[@]}))
[ "$jobs" -ge 2 ] || jobs=2
commitOf() { if [ "$1" = "$root" ]; then cat .device/commit; else cat "$1/.commit"; fi; }
for b in "${builds[@]:1}"; do
    (cd "$b" && cmake --preset gpu -DCMAKE_PREFIX_PATH="$prefix" -DRTRT_MODEL_DIR="$RTRT_MODEL_DIR" \
        -DRTRT_BUILD_TESTS=OFF >/dev/null && cmake --build --preset gpu -j "$jobs" --target rtrt \
        >"$b/build.log" 2>&1) || echo "build of $(commitOf "$b") failed" &
done
cmake --preset gpu -DCMAKE_PREFIX_PATH="$prefix" -DRTRT_MODEL_DIR="$RTRT_MODEL_DIR" >/dev/null 2>&1
cmake --build --preset gpu -j "$jobs" --target rtrt rtrt_gpu_tests >"$out/build.log" 2>&1 ||
    { grep -m20 -A5 error "$out/build.log"; exit 1; }
wait
rm -f "$out/build.log"
{
    nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
    build/gpu/tests/rtrt_gpu_tests 2>&1 | grep -E "FAILED|PASSED|tests ran" | tail -8
    for round in $(seq "${RTRT_ROUNDS:-2}"); do
        for b in "${builds[@]}"; do
            c=$(commitOf "$b")
            echo "== round $round: $c"
            RTRT_COMMIT=$c "$b/build/gpu/game/rtrt" bench gpu -o "$out/gpu-$c-$round.json" | tail -7
            [ "${RTRT_GRID:-1}" = 0 ] ||
                RTRT_COMMIT=$c "$b/build/gpu/game/rtrt" bench grid --counts 1000,10000,100000 \
                    --frames 100 -o "$out/grid-$c-$round.json" | tail -4
            [ "${RTRT_FRAME:-1}" = 0 ] ||
                RTRT_COMMIT=$c "$b/build/gpu/game/rtrt" bench frame assets/scenes/demo_glass.json \
                    assets/scenes/demo_1000_instances.json --size 1920x1080 \
                    -o "$out/frame-$c-$round.json" | tail -3
        done
    done
} 2>&1 | tee "$out/variants.log"
# At most 8 files come back from $OUT: the JSON travels as one tar beside the log.
(cd "$out" && tar -cf results.tar ./*.json && rm -f ./*.json)
