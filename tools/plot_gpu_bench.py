#!/usr/bin/python3
"""Plots the GPU benchmarks (`rtrt bench gpu` and `rtrt bench grid` JSON) against OptiX 9.0's times
on the same GPU and scenes, and optionally against a baseline commit measured in the same device
round (tools/device/pack.sh RTRT_BASELINE), and prints the README's tables as Markdown.

usage: tools/plot_gpu_bench.py GPU.json GRID.json OUT.png [BASELINE_GPU.json BASELINE_GRID.json]
Needs Debian's python3-matplotlib.
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# NVIDIA OptiX 9.0 on the H100 (no RT cores), as given by the CUDA issue.
OPTIX_PAPER_MS = {"cube": 0.174, "teapot": 0.277, "dragon_res4": 0.410, "dragon_res2": 0.796,
                  "dragon": 1.080}
OPTIX_GRID_TLAS_MS = {1000: 0.19, 10000: 0.25, 100000: 0.38, 1000000: 1.47}
OPTIX_GRID_TRACE_MS = {1000: 3.9, 10000: 7.1, 100000: 10.7, 1000000: 13.3}


def load(path):
    with open(path) as f:
        return json.load(f)


def main(gpu_path, grid_path, target, base_gpu_path=None, base_grid_path=None):
    gpu, grid = load(gpu_path), load(grid_path)
    base_gpu = load(base_gpu_path) if base_gpu_path else None
    base_grid = load(base_grid_path) if base_grid_path else None
    fig, (ax_paper, ax_grid) = plt.subplots(1, 2, figsize=(12, 4.5))

    models = [m for m in gpu["models"] if m["model"] in OPTIX_PAPER_MS]
    names = [m["model"] for m in models]
    series = [("rtrt", [m["trace_ms_median"] for m in models])]
    if base_gpu:
        by_name = {m["model"]: m for m in base_gpu["models"]}
        series.append((f'rtrt {base_gpu["machine"]["commit"]} (before)',
                       [by_name[n]["trace_ms_median"] for n in names]))
    series.append(("OptiX 9.0", [OPTIX_PAPER_MS[n] for n in names]))
    width = 0.8 / len(series)
    for i, (label, values) in enumerate(series):
        ax_paper.bar([j + i * width for j in range(len(names))], values, width, label=label)
    ax_paper.set_xticks([j + 0.4 - width / 2 for j in range(len(names))],
                        [f'{m["model"]}\n{m["triangles"]:,} tris' for m in models], fontsize=8)
    ax_paper.set_ylabel("trace ms (median of 200)")
    ax_paper.set_title("Paper scene, 1920x1080, depth 2")
    ax_paper.legend()

    counts = [r["instances"] for r in grid["rows"]]
    ax_grid.plot(counts, [r["trace_ms"] for r in grid["rows"]], "o-", label="rtrt trace")
    if base_grid:
        ax_grid.plot(counts, [r["trace_ms"] for r in base_grid["rows"]], "o:",
                     label=f'rtrt trace {base_grid["machine"]["commit"]} (before)')
    ax_grid.plot(counts, [OPTIX_GRID_TRACE_MS[c] for c in counts], "s--", label="OptiX 9.0 trace")
    ax_grid.plot(counts, [r["tlas_build_ms"] for r in grid["rows"]], "o-", label="rtrt TLAS build")
    ax_grid.plot(counts, [OPTIX_GRID_TLAS_MS[c] for c in counts], "s--", label="OptiX 9.0 TLAS build")
    ax_grid.set_xscale("log")
    ax_grid.set_yscale("log")
    ax_grid.set_xlabel("instances of dragon res4")
    ax_grid.set_ylabel("ms (median of 200)")
    ax_grid.set_title("Instance grid, TLAS rebuilt every frame")
    ax_grid.legend(fontsize=8)
    m = gpu["machine"]
    fig.suptitle(f'{m["gpu"]}, {m["date"]}, commit {m["commit"]}', fontsize=9)
    fig.tight_layout()
    fig.savefig(target, dpi=110)

    print("| model | triangles | rtrt trace ms | OptiX 9.0 ms | rtrt / OptiX | G rays/s | GPU bytes per triangle |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for mo in gpu["models"]:
        optix = OPTIX_PAPER_MS.get(mo["model"])
        ratio = f'{mo["trace_ms_median"] / optix:.2f}' if optix else "—"
        print(f'| {mo["model"]} | {mo["triangles"]:,} | {mo["trace_ms_median"]:.3f} | '
              f'{optix if optix else "—"} | {ratio} | {mo["grays_per_s"]:.2f} | '
              f'{mo["bytes_per_triangle"]:.0f} |')
    print()
    print("| instances | update ms | TLAS build ms (OptiX) | refit ms | trace ms (OptiX) | total ms | M rays | GPU bytes per instance |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in grid["rows"]:
        c = r["instances"]
        print(f'| {c:,} | {r["update_ms"]:.3f} | {r["tlas_build_ms"]:.3f} ({OPTIX_GRID_TLAS_MS[c]}) | '
              f'{r.get("tlas_refit_ms", float("nan")):.3f} | {r["trace_ms"]:.2f} ({OPTIX_GRID_TRACE_MS[c]}) | '
              f'{r["total_ms"]:.2f} | {r["rays"] / 1e6:.2f} | {r["bytes_per_instance"]:.0f} |')


if __name__ == "__main__":
    if len(sys.argv) not in (4, 6):
        sys.exit(__doc__)
    main(*sys.argv[1:])
