#!/usr/bin/env bash
# A/B round on the device machine: build this tree (rtrt and its GPU tests) and the baseline of
# .device/baseline (rtrt alone) side by side, run the GPU tests, then bench gpu on every paper
# model and bench frame on the 1080p demos, this tree and the baseline one after the other.
# RTRT_GRID=1 adds bench grid, two rounds alternating tree and baseline.
# Expects .device/ from tools/device/pack.sh (RTRT_BASELINE=...).
set -uo pipefail
source "$(dirname "$0")/ab_build.sh"
echo "== this tree $RTRT_COMMIT"; $r bench gpu -o $out/gpu.json | tail -9
echo "== baseline $bc"; RTRT_COMMIT=$bc $b bench gpu -o $out/base-gpu.json | tail -9
scenes="assets/scenes/demo_glass.json assets/scenes/demo_1000_instances.json assets/scenes/demo_crowd.json"
echo "== this tree $RTRT_COMMIT"; $r bench frame $scenes --size 1920x1080 -o $out/frame.json | tail -4
echo "== baseline $bc"; RTRT_COMMIT=$bc $b bench frame $scenes --size 1920x1080 -o $out/base-frame.json | tail -4
if [ "${RTRT_GRID:-0}" = 1 ]; then
    for round in 1 2; do
        echo "== grid round $round: this tree $RTRT_COMMIT"; $r bench grid -o $out/grid-$round.json | tail -5
        echo "== grid round $round: baseline $bc"; RTRT_COMMIT=$bc $b bench grid -o $out/base-grid-$round.json | tail -5
    done
fi
