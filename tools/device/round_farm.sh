#!/usr/bin/env bash
# The farm's tasks on the GPU: builds rtrt for sm_90 (no OpenImageIO, so PPM frames), runs
# `rtrt farm --local --backend cuda` of demo_physics in 4 shards, and checks each frame byte for
# byte against one `rtrt play --headless --backend cuda` run of the whole sequence. The device
# machine has no ffmpeg, so the assembly is expected to fail there (exit 1, frames kept).
# Leaves farm-gpu.log in $OUT. Expects .device/ from tools/device/pack.sh.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
out=${OUT:-$root/build/device-out}
mkdir -p "$out"
prefix=$root/.device/prefix/usr
export LD_LIBRARY_PATH=$prefix/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
export RTRT_MODEL_DIR=$root/.device/models
export PATH=/usr/local/cuda/bin:$PATH
{
    nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
    echo "commit $(cat "$root/.device/commit" 2>/dev/null || echo unknown)"
    cmake --preset gpu -DCMAKE_PREFIX_PATH="$prefix" -DRTRT_MODEL_DIR="$RTRT_MODEL_DIR" \
        -DRTRT_BUILD_TESTS=OFF >/dev/null && cmake --build --preset gpu -j 16 --target rtrt \
        >"$out/build.log" 2>&1 || { grep -m20 -A5 error "$out/build.log"; exit 1; }
    rtrt=$root/build/gpu/game/rtrt
    work=$(mktemp -d)
    frames=${RTRT_FARM_FRAMES:-240}
    size=${RTRT_FARM_SIZE:-1920x1080}
    "$rtrt" play demo_physics --headless --frames "$frames" --size "$size" --backend cuda \
        -o "$work/ref_%06d.ppm" | tail -1
    "$rtrt" farm demo_physics --frames "0:$frames" --shards 4 --size "$size" --backend cuda \
        --format ppm -o "$work/job" --local 2>&1 | grep -v "^rtrt play:"
    echo "farm exit ${PIPESTATUS[0]} (1 expected: no ffmpeg here)"
    differ=0
    for ((i = 0; i < frames; i++)); do
        f=$(printf '%06d' "$i")
        cmp -s "$work/ref_$f.ppm" "$work/job/frames/frame_$f.ppm" || { differ=$((differ + 1)); echo "frame $i differs"; }
    done
    echo "frames differing from the single run: $differ of $frames"
    "$rtrt" farm --status "$work/job"
    echo "status exit $? (3 expected: no video)"
} 2>&1 | tee "$out/farm-gpu.log"
