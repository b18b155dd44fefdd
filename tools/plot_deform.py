#!/usr/bin/python3
"""Plots `rtrt bench deform` results: the trace time of the refit BLAS against fresh SAH and LBVH
builds of the same deformed triangles over the animation (the quality drift), and each frame's
BLAS stage time under the three policies; prints the policy table as Markdown for the README.

usage: tools/plot_deform.py OUT.png RESULT.json[:FRAMES.csv] [RESULT.json[:FRAMES.csv] ...]
Needs Debian's python3-matplotlib.
"""
import csv
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(target, sources):
    fig, axes = plt.subplots(len(sources), 2, figsize=(12, 4 * len(sources)), squeeze=False)
    for row, source in enumerate(sources):
        result, _, frames = source.partition(":")
        with open(result) as f:
            report = json.load(f)
        name = report["scene"].removesuffix(".json")
        drift = report["drift"]
        ax = axes[row][0]
        xs = [d["frame"] for d in drift]
        ax.plot(xs, [d["refit_trace_ms"] for d in drift], "o-", label="refit every frame")
        ax.plot(xs, [d["fresh_sah_trace_ms"] for d in drift], "s-", label="fresh SAH build")
        ax.plot(xs, [d["fresh_lbvh_trace_ms"] for d in drift], "^-", label="fresh LBVH (rebuild)")
        ax.set_title(f"{name}: trace of the deformed BLAS")
        ax.set_xlabel("frame (60 fps)")
        ax.set_ylabel("trace ms, %dx%d" % (report["width"], report["height"]))
        ax.set_ylim(bottom=0)
        ax.legend()
        if frames:
            with open(frames) as f:
                rows = list(csv.DictReader(f))[1:]  # frame 0 admits the mesh
            ax = axes[row][1]
            for policy in ("refit", "rebuild", "adaptive"):
                ax.plot([int(r["frame"]) for r in rows], [float(r[policy + "_blas_ms"]) for r in rows],
                        label=policy, linewidth=0.8)
            ax.set_title(f"{name}: BLAS stage per frame")
            ax.set_xlabel("frame (60 fps)")
            ax.set_ylabel("ms")
            ax.set_ylim(bottom=0)
            ax.legend()
        print(f"\n{name} ({report['deforming_triangles']:,} triangles, "
              f"{report['width']}x{report['height']}, {report['machine'].get('gpu', '')}, "
              f"{report['machine'].get('commit', '')}):\n")
        print("| policy | deform ms | BLAS ms | trace ms | frame ms | rebuilds | BLAS Mtri/ms |")
        print("|---|---:|---:|---:|---:|---:|---:|")
        for p in report["policies"]:
            print(f"| {p['policy']} | {p['deform_ms']:.3f} | {p['blas_ms']:.3f} | "
                  f"{p['trace_ms']:.3f} | {p['frame_ms']:.3f} | {p['rebuilds']} | "
                  f"{p['blas_mtri_per_ms']:.2f} |")
    fig.tight_layout()
    fig.savefig(target, dpi=90)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
