#!/usr/bin/python3
"""Plots a `rtrt bench cpu` JSON result (frame time and BLAS build time per model and builder) and
prints its table as Markdown for the README.

usage: tools/plot_bench.py bench/results/cpu-....json docs/images/bench_cpu.png
Needs Debian's python3-matplotlib.
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

EMBREE_DRAGON_MS = 98.0  # Embree 3, same scene and machine kind (the foundation issue's reference)


def main(source, target):
    with open(source) as f:
        report = json.load(f)
    models = [m for m in report["models"]]
    builders = list(models[0]["builders"].keys())
    fig, (ax_frame, ax_build) = plt.subplots(1, 2, figsize=(12, 4.5))
    width = 0.8 / len(builders)
    for i, builder in enumerate(builders):
        xs = [j + i * width for j in range(len(models))]
        ax_frame.bar(xs, [m["builders"][builder]["frame_ms"] for m in models], width, label=builder)
        ax_build.bar(xs, [max(m["builders"][builder]["build_ms"], 1e-3) for m in models], width,
                     label=builder)
    labels = [f'{m["model"]}\n{m["triangles"]:,} tris' for m in models]
    for ax in (ax_frame, ax_build):
        ax.set_xticks([j + 0.4 - width / 2 for j in range(len(models))], labels, fontsize=8)
        ax.legend(title="BLAS builder")
    ax_frame.axhline(EMBREE_DRAGON_MS, color="black", linestyle=":", linewidth=1)
    ax_frame.text(0, EMBREE_DRAGON_MS * 1.03, "Embree 3, full dragon", fontsize=8)
    ax_frame.set_ylabel("CPU frame time, ms (median)")
    ax_frame.set_title("Paper scene, 1920x1080, max depth 2")
    ax_build.set_yscale("log")
    ax_build.set_ylabel("BLAS build time, ms (log)")
    ax_build.set_title("BLAS build")
    machine = report["machine"]
    fig.suptitle(f'{machine["cpu"]}, {machine["threads"]} threads, {machine["date"]}, commit {machine["commit"]}',
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(target, dpi=110)
    print("| model | triangles | builder | BLAS build ms | SAH cost | frame ms | M rays | M rays/s |")
    print("|---|---:|---|---:|---:|---:|---:|---:|")
    for m in models:
        for b in builders:
            v = m["builders"][b]
            print(f'| {m["model"]} | {m["triangles"]:,} | {b} | {v["build_ms"]:.1f} | '
                  f'{v["sah_cost"]:.2f} | {v["frame_ms"]:.1f} | {v["rays"] / 1e6:.2f} | '
                  f'{v["mrays_per_s"]:.1f} |')


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
