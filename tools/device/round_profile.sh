#!/usr/bin/env bash
# Nsight Compute sections of the trace kernels on the device machine: builds rtrt for sm_90 and
# profiles one launch of the paper scene's trace kernel (the full dragon) and one of the instance
# grid's (1,000 dragons), after warm-up launches. Leaves each report as text (profile-*.txt) and
# the source-level counters as CSV in $OUT. The clocks stay as they are (METHOD.md), so the
# durations ncu prints are the replayed pass's, not a benchmark: take the ratios and stall
# reasons from here and the times from rtrt bench.
set -uo pipefail
source "$(dirname "$0")/device_env.sh"
cmake --preset gpu -DCMAKE_PREFIX_PATH="$prefix" -DRTRT_MODEL_DIR="$RTRT_MODEL_DIR" \
    -DRTRT_BUILD_TESTS=OFF -DCMAKE_CUDA_FLAGS="-lineinfo" >/dev/null 2>&1
cmake --build --preset gpu -j 16 --target rtrt >"$out/build.log" 2>&1 ||
    { grep -m20 -A5 error "$out/build.log"; exit 1; }
rm -f "$out/build.log"
rtrt=build/gpu/game/rtrt
sections=(--section SpeedOfLight --section LaunchStats --section Occupancy
    --section WarpStateStats --section SchedulerStats --section MemoryWorkloadAnalysis
    --section MemoryWorkloadAnalysis_Tables --section InstructionStats
    --section ComputeWorkloadAnalysis --section SourceCounters)
profile() {
    local name=$1
    shift
    ncu --clock-control none -k regex:TraceKernel --launch-skip 25 --launch-count 1 \
        "${sections[@]}" -o "$out/$name" -f "$@" >"$out/$name.log" 2>&1 || tail -20 "$out/$name.log"
    ncu --import "$out/$name.ncu-rep" --page details >"$out/profile-$name.txt" 2>&1
    ncu --import "$out/$name.ncu-rep" --page source --csv --print-source sass \
        >"$out/source-$name.csv" 2>/dev/null
    gzip -f "$out/source-$name.csv"
    rm -f "$out/$name.log"
}
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee "$out/device.txt"
profile dragon "$rtrt" bench gpu --models dragon --frames 10
profile grid "$rtrt" bench grid --counts 1000 --frames 10
ls -la "$out"
