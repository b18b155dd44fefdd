#!/usr/bin/env bash
# A GPU round of the binaries that tools/device/pack_binaries.sh built on the CPU machine (carry
# [".device-bin"]): the GPU tests, the traversal forms' frames compared pixel by pixel, then bench
# grid, bench gpu, bench frame (the four played demos at 1920x1080) and bench materials (the glTF
# PBR scenes), RTRT_ROUNDS times (default 2), this build, .device-bin/rtrt-baseline (if packed)
# and any rtrt-variant-NAME in turn, after comparing their frames with this build's.
# Leaves round.log, gpu_tests.log and results.tar (the JSON) in $OUT.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
out=${OUT:-$root/build/device-out}
mkdir -p "$out"
pack=$root/.device-bin
# Binaries packed gzipped, to keep the carry under its limit.
for packed in "$pack"/rtrt*.gz; do [ -e "$packed" ] && gunzip -f "$packed" && chmod +x "${packed%.gz}"; done
[ -x "$pack/rtrt" ] || { echo "round_binaries: no $pack/rtrt (tools/device/pack_binaries.sh, carry [\".device-bin\"])" >&2; exit 1; }
export LD_LIBRARY_PATH=$pack/lib:/usr/local/cuda/lib64:/usr/local/cuda/lib:${LD_LIBRARY_PATH:-}
export RTRT_MODEL_DIR=$pack/models RTRT_COMMIT=$(cat "$pack/commit")
log=$out/round.log
say() { echo "$@" | tee -a "$log"; }
# The tests read the sources and models under the CPU machine's paths, compiled into them.
source_dir=$(cat "$pack/source_dir")
if [ "$source_dir" != "$root" ] && [ ! -e "$source_dir" ]; then
    mkdir -p "$(dirname "$source_dir")" && ln -s "$root" "$source_dir"
fi
mkdir -p .cache && { [ -e .cache/models ] || ln -s "$pack/models" .cache/models; }
say "$(date -u) commit $RTRT_COMMIT, $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader)"
for binary in "$pack"/rtrt*; do
    missing=$(ldd "$binary" | grep "not found")
    [ -z "$missing" ] || { say "$binary: missing libraries: $missing"; exit 1; }
done
"$pack/rtrt_gpu_tests" >"$out/gpu_tests.log" 2>&1
say "rtrt_gpu_tests exit $?: $(grep -E "^\[  (PASSED|FAILED) |^\[  SKIPPED \] [0-9]+ test|test suites ran" "$out/gpu_tests.log" | tail -40)"
# The traversal forms' frames, equal bit for bit (the tests compare them at 320 x 180).
frames=$(mktemp -d)
for scene in demo_physics demo_1000_instances demo_crowd; do
    rendered=1
    for form in nested single; do
        "$pack/rtrt" render "assets/scenes/$scene.json" --backend cuda --traversal "$form" \
            --size 640x360 -o "$frames/$scene-$form.pfm" >/dev/null 2>&1 ||
            { say "$scene: the $form render failed"; rendered=0; }
    done
    if [ "$rendered" = 0 ]; then
        continue
    elif cmp -s "$frames/$scene-nested.pfm" "$frames/$scene-single.pfm"; then
        say "$scene: nested and single frames equal"
    else
        say "$scene: nested and single frames DIFFER"
    fi
done
results=$(mktemp -d)
builds=("$pack/rtrt")
if [ -x "$pack/rtrt-baseline" ]; then
    builds+=("$pack/rtrt-baseline")
else
    say "no rtrt-baseline packed: this build alone is timed"
fi
# Variants packed by hand beside it (rtrt-variant-NAME, an experiment's build of this tree).
for variant in "$pack"/rtrt-variant-*; do [ -x "$variant" ] && builds+=("$variant"); done
# The label of a build in the log and the result files.
label() {
    case "$1" in
    "$pack/rtrt") echo "$RTRT_COMMIT" ;;
    "$pack/rtrt-baseline") cat "$pack/baseline_commit" ;;
    *) echo "$RTRT_COMMIT-${1##*/rtrt-variant-}" ;;
    esac
}
# Every other build's frames (the default traversal form) against this build's, rendered once.
scenes="dragon demo_physics demo_1000_instances demo_crowd demo_glass"
render() {
    "$1" render "assets/scenes/$2.json" --backend cuda --size 640x360 \
        -o "$frames/$2-$(label "$1").pfm" >/dev/null 2>&1
}
if [ "${#builds[@]}" -gt 1 ]; then
    for scene in $scenes; do render "$pack/rtrt" "$scene"; done
fi
for rtrt in "${builds[@]:1}"; do
    for scene in $scenes; do
        render "$rtrt" "$scene"
        if cmp -s "$frames/$scene-$RTRT_COMMIT.pfm" "$frames/$scene-$(label "$rtrt").pfm"; then
            say "$scene: $(label "$rtrt") frame equals $RTRT_COMMIT's"
        else
            say "$scene: $(label "$rtrt") frame DIFFERS from $RTRT_COMMIT's (or a render failed)"
        fi
    done
done
demos=$(for d in demo_glass demo_1000_instances demo_physics demo_crowd; do echo "assets/scenes/$d.json"; done)
for round in $(seq "${RTRT_ROUNDS:-2}"); do
    for rtrt in "${builds[@]}"; do
        commit=$(label "$rtrt")
        say "== round $round: $commit"
        say "$(RTRT_COMMIT=$commit "$rtrt" bench grid --counts 1000,10000 --frames 50 \
            -o "$results/grid-$commit-$round.json" 2>&1 | tail -4 | head -3)"
        say "$(RTRT_COMMIT=$commit "$rtrt" bench gpu --frames 100 \
            -o "$results/gpu-$commit-$round.json" 2>&1 | tail -7 | head -6)"
        # The played demos: they take the nested kernels, which the grid does not.
        say "$(RTRT_COMMIT=$commit "$rtrt" bench frame $demos --size 1920x1080 --frames 200 \
            -o "$results/frame-$commit-$round.json" 2>&1 | tail -6 | head -5)"
        # glTF's PBR materials, whose kernels the scenes above use only in demo_crowd's walkers.
        say "$(RTRT_COMMIT=$commit "$rtrt" bench materials assets/models/pbr_showcase.gltf \
            assets/models/textured_quads.gltf --frames 100 \
            -o "$results/materials-$commit-$round.json" 2>&1 | tail -7)"
    done
done
tar -C "$results" -cf "$out/results.tar" .
say "$(date -u) done"
