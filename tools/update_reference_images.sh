#!/usr/bin/env bash
# Re-renders tests/reference/*.png with the CPU back end. Run it only when a change to the
# renderer is meant to change the images, and say so in the commit.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
rtrt=${RTRT:-$root/build/release/game/rtrt}
out=$root/tests/reference
size=200x150
"$rtrt" render default -o "$out/default.png" --size $size
for scene in reflective_sphere refractive_sphere teapot_shadow; do
    "$rtrt" render "$root/assets/scenes/$scene.json" -o "$out/$scene.png" --size $size
done
