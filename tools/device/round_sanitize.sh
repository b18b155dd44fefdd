#!/usr/bin/env bash
# The CPU test suite under AddressSanitizer and UndefinedBehaviorSanitizer (CMake preset
# `sanitize`), built and run on the GPU machine's 16 cores (here it would take most of an hour
# on 2). Labels gpu and window are left out: they need CUDA and a display. Expects .device/.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
out=${OUT:-$root/build/device-out}
mkdir -p "$out"
prefix=$root/.device/prefix/usr
export LD_LIBRARY_PATH=$prefix/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}
export RTRT_MODEL_DIR=$root/.device/models
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
cmake --preset sanitize -DRTRT_WITH_OIIO=OFF -DCMAKE_PREFIX_PATH="$prefix" \
    -DRTRT_MODEL_DIR="$RTRT_MODEL_DIR" >"$out/configure.log" 2>&1 || { tail -30 "$out/configure.log"; exit 1; }
cmake --build --preset sanitize -j 16 >"$out/build.log" 2>&1 || { grep -m20 -A5 error "$out/build.log"; exit 1; }
rm -f "$out/build.log"
ctest --test-dir build/sanitize -LE "gpu|window" -j 16 --output-on-failure 2>&1 | tee "$out/sanitize_tests.log" | tail -30
