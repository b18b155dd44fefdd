#!/usr/bin/env bash
# Prepares .device/, the folder the GPU machine needs beside the working tree (it has CUDA, CMake
# and ninja but no package registry): Debian 12 development packages unpacked into a private
# prefix, the fetched models and the commit. Call the device tool with carry [".device"]; after a
# new commit, refresh just the commit: git rev-parse --short HEAD > .device/commit
#
# RTRT_BASELINE=<commit> tools/device/pack.sh --baseline-only adds (or replaces) .device/baseline,
# the source of an earlier commit that round.sh then benchmarks beside the working tree, so that
# a change is measured against what it changes in one run on one machine.
#
# tools/device/pack.sh --variant <commit>... adds the source of each commit under
# .device/variants/, for round_variants.sh (--variant alone clears them).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
dest=$root/.device
add_baseline() {
    rm -rf "$dest/baseline"
    mkdir -p "$dest/baseline"
    git -C "$root" archive "$RTRT_BASELINE" | tar -x -C "$dest/baseline"
    git -C "$root" rev-parse --short "$RTRT_BASELINE" >"$dest/baseline/.commit"
    echo "baseline $(cat "$dest/baseline/.commit") in $dest/baseline"
}
if [ "${1:-}" = "--variant" ]; then
    shift
    rm -rf "$dest/variants"
    for c in "$@"; do
        short=$(git -C "$root" rev-parse --short "$c")
        mkdir -p "$dest/variants/$short"
        git -C "$root" archive "$c" | tar -x -C "$dest/variants/$short"
        echo "$short" >"$dest/variants/$short/.commit"
        echo "variant $short in $dest/variants/$short"
    done
    exit 0
fi
if [ "${1:-}" = "--baseline-only" ]; then
    add_baseline
    exit 0
fi
rm -rf "$dest"
mkdir -p "$dest/debs" "$dest/prefix" "$dest/models"
cd "$dest/debs"
# Header-only or static libraries, plus the runtimes of TBB and tinygltf (with its stb image
# decoder); their glibc 2.36 builds run on 2.39 there.
apt-get download -q libglm-dev libtbb-dev libtbb12 libtbbmalloc2 libtbbbind-2-5 libhwloc15 libcli11-dev nlohmann-json3-dev \
    libgtest-dev zlib1g-dev libxxhash-dev libtinygltf-dev libtinygltf2d libstb0 2>&1 | grep -v "unsandboxed" || true
for deb in *.deb; do dpkg -x "$deb" "$dest/prefix"; done
rm -rf "$dest/debs" "$dest/prefix/usr/share/doc"
"$root/tools/fetch_models.sh" >/dev/null
cp "$root"/.cache/models/* "$dest/models/"
git -C "$root" rev-parse --short HEAD >"$dest/commit"
du -sh "$dest"
if [ -n "${RTRT_BASELINE:-}" ]; then add_baseline; fi
