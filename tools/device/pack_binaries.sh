#!/usr/bin/env bash
# Builds the device machine's binaries here, on the CPU machine, into .device-bin/, so that a
# device call spends its time running them rather than compiling (a source build there takes 4-8
# minutes of the session's device time; a round of these binaries takes about one). The build is
# build/gpu configured as there: sm_90, no OpenImageIO, no window, no Embree (neither is on the
# device machine). .device-bin/ holds the stripped and gzipped rtrt and rtrt_gpu_tests, the
# runtime libraries from .device/ (pack.sh first), the models and the commit. Carry
# [".device-bin"] and run tools/device/round_binaries.sh. An experiment's build of this tree may
# be added by hand as rtrt-variant-NAME(.gz); the round times it too.
#
# tools/device/pack_binaries.sh --baseline <commit> also builds that commit's rtrt (a worktree
# under build/, rtrt alone) as .device-bin/rtrt-baseline, which the round benchmarks beside it.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
dest=$root/.device-bin
baseline=""
if [ "${1:-}" = "--baseline" ]; then baseline=${2:?--baseline needs a commit}; fi
[ -d "$root/.device/prefix" ] || { echo "pack_binaries: run tools/device/pack.sh first (.device/prefix is missing)" >&2; exit 1; }
# Builds, from the tree $1 into the build folder $2, rtrt and, with $3 = tests, the GPU tests.
build() {
    local tests=OFF targets=rtrt
    if [ "${3:-}" = tests ]; then tests=ON targets="rtrt rtrt_gpu_tests"; fi
    cmake -S "$1" -B "$2" --preset gpu -DRTRT_WINDOW=OFF -DCMAKE_DISABLE_FIND_PACKAGE_embree=ON \
        -DRTRT_BUILD_TESTS=$tests -DRTRT_MODEL_DIR="$root/.cache/models" >/dev/null
    cmake --build "$2" -j "$(nproc)" --target $targets
}
(cd "$root" && build "$root" "$root/build/gpu" tests)
rm -rf "$dest"
mkdir -p "$dest/lib"
# Stripped and gzipped (round_binaries.sh unpacks them): the carry and the working tree together
# must stay under 64 MiB.
strip -o "$dest/rtrt" "$root/build/gpu/game/rtrt"
strip -o "$dest/rtrt_gpu_tests" "$root/build/gpu/tests/rtrt_gpu_tests"
gzip -9 "$dest/rtrt" "$dest/rtrt_gpu_tests"
cp -a "$root"/.device/prefix/usr/lib/x86_64-linux-gnu/*.so* "$dest/lib/"
cp -a "$root/.device/models" "$dest/models"
# The commit, marked -dirty when the build holds uncommitted changes.
git -C "$root" describe --always --dirty --abbrev=7 --exclude='*' >"$dest/commit"
# The tests find the sources and models under the paths compiled into them.
echo "$root" >"$dest/source_dir"
if [ -n "$baseline" ]; then
    # The worktree goes after the build; its build folder stays, for the next baseline's build.
    tree=$root/build/baseline-src
    git -C "$root" worktree remove --force "$tree" 2>/dev/null || rm -rf "$tree"
    git -C "$root" worktree add --detach "$tree" "$baseline" >/dev/null
    (cd "$tree" && build "$tree" "$root/build/baseline-gpu")
    strip -o "$dest/rtrt-baseline" "$root/build/baseline-gpu/game/rtrt"
    gzip -9 "$dest/rtrt-baseline"
    git -C "$root" rev-parse --short "$baseline" >"$dest/baseline_commit"
    git -C "$root" worktree remove --force "$tree"
fi
du -sh "$dest"
