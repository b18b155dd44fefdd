#!/usr/bin/env bash
# Prepares what the GPU machine needs to run the window test with CUDA-GL interop (its image has
# no X server and no GL development files): Debian 12 packages for Xvfb, Mesa (the X server's
# own GLX), the GLVND dispatch libraries, GLFW, Dear ImGui and pkg-config. They are about 62 MB,
# more than one device call may carry beside the tree, so they are split in two halves:
# .gl1/ (LLVM, which Mesa's software rasteriser links) and .gl2/ (the rest). round_window.sh
# unpacks each into /tmp/glroot on the machine, which keeps it while the machine stays warm:
#   call 1: carry [".gl1"], command: bash tools/device/round_window.sh unpack .gl1
#   call 2 (within the warm period): carry [".device", ".gl2"],
#           command: bash tools/device/round_window.sh unpack .gl2 run
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
for part in gl1 gl2; do
    grep -qx "/.$part/" "$root/.git/info/exclude" 2>/dev/null || echo "/.$part/" >>"$root/.git/info/exclude"
    rm -rf "$root/.$part"
    mkdir -p "$root/.$part"
done
(cd "$root/.gl1" && apt-get download -q libllvm15 2>&1 | grep -v unsandboxed || true)
(cd "$root/.gl2" && apt-get download -q \
    xvfb xserver-common x11-xkb-utils xkb-data libxfont2 libpixman-1-0 libunwind8 libxau6 \
    libxdmcp6 libfontenc1 libfreetype6 libxkbfile1 libxaw7 libxt6 libxmu6 libxpm4 libsm6 libice6 \
    libxext6 libxrandr2 libxrender1 libxinerama1 libxcursor1 libxfixes3 libxi6 libx11-6 \
    libx11-xcb1 libxcb1 libxcb-glx0 libxcb-dri2-0 libxcb-dri3-0 libxcb-present0 libxcb-sync1 \
    libxcb-xfixes0 libxcb-randr0 libxcb-shm0 libxshmfence1 libxxf86vm1 libglfw3 libglvnd0 libgl1 \
    libglx0 libopengl0 libglx-mesa0 libgl1-mesa-dri libglapi-mesa libdrm2 libdrm-amdgpu1 \
    libdrm-radeon1 libdrm-nouveau2 libdrm-intel1 libpciaccess0 libsensors5 libz3-4 libelf1 \
    libedit2 libbsd0 libmd0 libxml2 libicu72 libtinfo6 libpng16-16 libbrotli1 libxkbcommon0 \
    libglfw3-dev libgl-dev libglx-dev libopengl-dev libimgui-dev libstb-dev libstb0 pkgconf \
    pkgconf-bin libpkgconf3 2>&1 | grep -v unsandboxed || true)
du -sh "$root/.gl1" "$root/.gl2"
