#!/usr/bin/env bash
# Prepares .device/, the folder the GPU machine needs beside the working tree (it has CUDA, CMake
# and ninja but no package registry): Debian 12 development packages unpacked into a private
# prefix, the fetched models and the commit. Call the device tool with carry [".device"]; after a
# new commit, refresh just the commit: git rev-parse --short HEAD > .device/commit
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
dest=$root/.device
rm -rf "$dest"
mkdir -p "$dest/debs" "$dest/prefix" "$dest/models"
cd "$dest/debs"
# Header-only or static libraries, plus TBB's runtime (its glibc 2.36 build runs on 2.39 there).
apt-get download -q libglm-dev libtbb-dev libtbb12 libtbbmalloc2 libtbbbind-2-5 libhwloc15 libcli11-dev nlohmann-json3-dev \
    libgtest-dev zlib1g-dev libxxhash-dev 2>&1 | grep -v "unsandboxed" || true
for deb in *.deb; do dpkg -x "$deb" "$dest/prefix"; done
rm -rf "$dest/debs" "$dest/prefix/usr/share/doc"
"$root/tools/fetch_models.sh" >/dev/null
cp "$root"/.cache/models/* "$dest/models/"
git -C "$root" rev-parse --short HEAD >"$dest/commit"
du -sh "$dest"
