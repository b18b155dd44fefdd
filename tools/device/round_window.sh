#!/usr/bin/env bash
# The window test on the GPU machine (see pack_window.sh): `unpack DIR` adds a half of the X/GL
# packages to /tmp/glroot; `run` builds rtrt with the window for sm_90, starts Xvfb with GLX,
# and runs ctest -L window with the CUDA back end under the NVIDIA GLX driver
# (__GLX_VENDOR_LIBRARY_NAME=nvidia), so frames reach the window through CUDA-GL interop. The
# screenshots and logs come back in $OUT. `profile` (after `run`, or instead of it: it builds
# rtrt alone) plays the 1080p demos in the window with vsync off and prints where a windowed
# frame's time goes: the stage medians rtrt prints at the end, each demo once as it plays and once
# with --finish-stages (the GPU finished after each display stage).
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
out=${OUT:-$root/build/device-out}
mkdir -p "$out"
glroot=/tmp/glroot
configure_window() {
    cmake -S . -B build/window -G Ninja -DCMAKE_BUILD_TYPE=Release -DRTRT_CUDA=ON \
        -DCMAKE_CUDA_ARCHITECTURES=90 -DRTRT_WITH_OIIO=OFF -DRTRT_WINDOW=ON \
        -DRTRT_WINDOW_TEST_XVFB=OFF -DRTRT_WINDOW_TEST_BACKEND=cuda \
        -DCMAKE_PREFIX_PATH="$prefix;$glroot/usr" -DRTRT_MODEL_DIR="$RTRT_MODEL_DIR" \
        >"$out/configure.log" 2>&1 || { tail -30 "$out/configure.log"; exit 1; }
}
setup_window() {
    [ -x "$glroot/usr/bin/Xvfb" ] || { echo "unpack .gl1 and .gl2 first" >&2; exit 1; }
    prefix=$root/.device/prefix/usr
    lib=x86_64-linux-gnu
    export LD_LIBRARY_PATH=$prefix/lib/$lib:$glroot/usr/lib/$lib:${LD_LIBRARY_PATH:-}
    export LIBGL_DRIVERS_PATH=$glroot/usr/lib/$lib/dri
    export PATH=/usr/local/cuda/bin:$glroot/usr/bin:$PATH
    export PKG_CONFIG_PATH=$glroot/usr/lib/$lib/pkgconfig:$glroot/usr/share/pkgconfig
    export PKG_CONFIG_SYSROOT_DIR=$glroot
    export RTRT_MODEL_DIR=$root/.device/models
    # Xvfb looks for xkbcomp and the keyboard data at built-in paths (a throwaway machine).
    [ -e /usr/bin/xkbcomp ] || ln -s "$glroot/usr/bin/xkbcomp" /usr/bin/xkbcomp
    [ -e /usr/share/X11/xkb ] || { mkdir -p /usr/share/X11 && ln -s "$glroot/usr/share/X11/xkb" /usr/share/X11/xkb; }
    Xvfb :5 -screen 0 1920x1080x24 +extension GLX >"$out/xvfb.log" 2>&1 &
    sleep 2
    export DISPLAY=:5 __GLX_VENDOR_LIBRARY_NAME=nvidia
}
while [ $# -gt 0 ]; do
    case "$1" in
        unpack)
            mkdir -p "$glroot"
            for deb in "$2"/*.deb; do dpkg -x "$deb" "$glroot"; done
            echo "unpacked $(ls "$2" | wc -l) packages from $2"
            shift 2
            ;;
        run)
            shift
            setup_window
            configure_window
            cmake --build build/window -j 16 --target rtrt rtrt_window_tests >"$out/build.log" 2>&1 ||
                { grep -m20 -A5 error "$out/build.log"; exit 1; }
            rm -f "$out/build.log"
            ctest --test-dir build/window -L window -V 2>&1 | tee "$out/window_tests.log"
            tar -C build/window/tests/window -cf "$out/window_shots.tar" .
            ;;
        profile)
            shift
            [ -n "${DISPLAY:-}" ] || setup_window
            configure_window
            cmake --build build/window -j 16 --target rtrt >"$out/build.log" 2>&1 ||
                { grep -m20 -A5 error "$out/build.log"; exit 1; }
            for scene in demo_1000_instances demo_crowd demo_glass; do
                for flag in "" --finish-stages; do
                    echo "== $scene ${flag:-(as it plays)}"
                    build/window/game/rtrt play "assets/scenes/$scene.json" --size 1920x1080 \
                        --no-vsync --frames 330 $flag 2>&1 | grep -E "medians|display:"
                done
            done
            ;;
        *)
            echo "usage: round_window.sh [unpack DIR]... [run] [profile]" >&2
            exit 2
            ;;
    esac
done
