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

# NVIDIA OptiX 9.0's times on the same scenes, per GPU (neither has RT cores), as the performance
# issues give them: on the H100 the TLAS build and the trace of the grid, on the H200 the trace and
# the whole frame (update, build and trace).
OPTIX = {
    "H100": {
        "paper": {"cube": 0.174, "teapot": 0.277, "dragon_res4": 0.410, "dragon_res2": 0.796,
                  "dragon": 1.080},
        "grid_tlas": {1000: 0.19, 10000: 0.25, 100000: 0.38, 1000000: 1.47},
        "grid_trace": {1000: 3.9, 10000: 7.1, 100000: 10.7, 1000000: 13.3},
    },
    "H200": {
        "paper": {"cube": 0.196, "teapot": 0.208, "dragon_res4": 0.443, "dragon_res3": 0.653,
                  "dragon_res2": 0.853, "dragon": 1.174},
        "grid_trace": {1000: 3.71, 10000: 6.69, 100000: 10.07, 1000000: 12.56},
        "grid_total": {1000: 3.90, 10000: 6.97, 100000: 10.44, 1000000: 13.98},
    },
}


def optix_for(gpu_name):
    for kind, figures in OPTIX.items():
        if kind in gpu_name:
            return figures
    sys.exit(f"no OptiX figures for {gpu_name}: only {', '.join(OPTIX)}")

def load(path):
    with open(path) as f:
        return json.load(f)


def main(gpu_path, grid_path, target, base_gpu_path=None, base_grid_path=None):
    gpu, grid = load(gpu_path), load(grid_path)
    base_gpu = load(base_gpu_path) if base_gpu_path else None
    base_grid = load(base_grid_path) if base_grid_path else None
    optix = optix_for(gpu["machine"]["gpu"])
    paper_ms = optix["paper"]
    fig, (ax_paper, ax_grid) = plt.subplots(1, 2, figsize=(12, 4.5))

    models = [m for m in gpu["models"] if m["model"] in paper_ms]
    names = [m["model"] for m in models]
    series = [("rtrt", [m["trace_ms_median"] for m in models])]
    if base_gpu:
        by_name = {m["model"]: m for m in base_gpu["models"]}
        series.append((f'rtrt {base_gpu["machine"]["commit"]} (before)',
                       [by_name[n]["trace_ms_median"] for n in names]))
    series.append(("OptiX 9.0", [paper_ms[n] for n in names]))
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
    ax_grid.plot(counts, [optix["grid_trace"][c] for c in counts], "s--", label="OptiX 9.0 trace")
    if "grid_tlas" in optix:
        ax_grid.plot(counts, [r["tlas_build_ms"] for r in grid["rows"]], "o-",
                     label="rtrt TLAS build")
        ax_grid.plot(counts, [optix["grid_tlas"][c] for c in counts], "s--",
                     label="OptiX 9.0 TLAS build")
    else:
        ax_grid.plot(counts, [r["total_ms"] for r in grid["rows"]], "o-",
                     label="rtrt update + build + trace")
        ax_grid.plot(counts, [optix["grid_total"][c] for c in counts], "s--",
                     label="OptiX 9.0 update + build + trace")
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
        reference = paper_ms.get(mo["model"])
        ratio = f'{mo["trace_ms_median"] / reference:.2f}' if reference else "—"
        print(f'| {mo["model"]} | {mo["triangles"]:,} | {mo["trace_ms_median"]:.3f} | '
              f'{reference if reference else "—"} | {ratio} | {mo["grays_per_s"]:.2f} | '
              f'{mo["bytes_per_triangle"]:.0f} |')
    print()
    tlas = "TLAS build ms (OptiX)" if "grid_tlas" in optix else "TLAS build ms"
    total = "total ms (OptiX)" if "grid_total" in optix else "total ms"
    print(f"| instances | update ms | {tlas} | refit ms | trace ms (OptiX) | {total} | M rays | GPU bytes per instance |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in grid["rows"]:
        c = r["instances"]
        build = f'{r["tlas_build_ms"]:.3f}'
        if "grid_tlas" in optix:
            build += f' ({optix["grid_tlas"][c]})'
        whole = f'{r["total_ms"]:.2f}'
        if "grid_total" in optix:
            whole += f' ({optix["grid_total"][c]})'
        print(f'| {c:,} | {r["update_ms"]:.3f} | {build} | '
              f'{r.get("tlas_refit_ms", float("nan")):.3f} | {r["trace_ms"]:.2f} ({optix["grid_trace"][c]}) | '
              f'{whole} | {r["rays"] / 1e6:.2f} | {r["bytes_per_instance"]:.0f} |')

if __name__ == "__main__":
    if len(sys.argv) not in (4, 6):
        sys.exit(__doc__)
    main(*sys.argv[1:])
