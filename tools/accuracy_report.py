#!/usr/bin/python3
"""Writes docs/accuracy.md and its plots from `rtrt bench accuracy` JSON results.

usage: tools/accuracy_report.py RESULT.json [RESULT.json ...] DOCS_DIR [--images DIR]

Each RESULT is one run (--backend cpu, cuda or both); their CPU and GPU columns are merged row by
row (rows match on scene and setting). The error of each setting is taken from the CPU run when
there is one, and the GPU's own error is shown next to it. --images is the folder that
`rtrt bench accuracy --images` filled: the report then also draws the reference images and the
difference images; without it, existing docs/images/accuracy_errors.png is kept.
Needs Debian's python3-matplotlib.
"""
import argparse
import json
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

# Difference images shown in the report: (scene, setting name).
ERROR_PICTURES = [
    ("dragon", "base: float"),
    ("dragon", "max depth 2"),
    ("dragon", "1 spp"),
    ("dragon", "Moller-Trumbore + fixed epsilon"),
    ("spheres", "naive quadratic"),
    ("spheres", "fixed epsilon 1e-4"),
]


def load(paths):
    runs = []
    for path in paths:
        with open(path) as f:
            runs.append((os.path.basename(path), json.load(f)))
    return runs


def merge(runs):
    """Rows keyed by (scene, name), in the order of the first run, with 'cpu'/'gpu' columns."""
    rows, order = {}, []
    for _, report in runs:
        # A CUDA run renders its reference on its host's CPU too; that time belongs to another
        # machine than the CPU run's, so its CPU column is left out.
        backends = {"cpu": ["cpu"], "cuda": ["gpu"], "both": ["cpu", "gpu"]}[report["backend"]]
        for row in report["rows"]:
            key = (row["scene"], row["name"])
            if key not in rows:
                rows[key] = {k: v for k, v in row.items() if k not in ("cpu", "gpu")}
                order.append(key)
            for backend in backends:
                if backend in row:
                    rows[key][backend] = row[backend]
    return [rows[k] for k in order]


def fmt(value, digits):
    if value is None:
        return "—"
    if isinstance(value, float) and math.isinf(value):
        return "∞"
    return f"{value:.{digits}f}"


def psnr_text(errors):
    return "∞" if errors.get("psnr_db") is None else f"{errors['psnr_db']:.1f}"


def table(rows, have_gpu):
    head = "| scene | knob | setting | CPU ms |"
    rule = "|---|---|---|---:|"
    if have_gpu:
        head += " GPU ms |"
        rule += "---:|"
    head += " RMSE | PSNR dB | outliers % | mismatch % |"
    rule += "---:|---:|---:|---:|"
    if have_gpu:
        head += " GPU RMSE | GPU outliers % | GPU mismatch % |"
        rule += "---:|---:|---:|"
    lines = [head, rule]
    for r in rows:
        cpu, gpu = r.get("cpu"), r.get("gpu")
        errors = cpu or gpu
        line = f"| {r['scene']} | {r['knob']} | {r['name']} | {fmt(cpu and cpu['ms'], 1)} |"
        if have_gpu:
            line += f" {fmt(gpu and gpu['ms'], 2)} |"
        if errors is None:  # the reference row of a CUDA-only run (its CPU column is left out)
            line += " — | — | — | — |"
        else:
            line += (f" {errors['rmse']:.5f} | {psnr_text(errors)} |"
                     f" {100 * errors['outlier_rate']:.3f} | {100 * errors['mismatch_rate']:.3f} |")
        if have_gpu:
            if gpu:
                line += (f" {gpu['rmse']:.5f} | {100 * gpu['outlier_rate']:.3f} |"
                         f" {100 * gpu['mismatch_rate']:.3f} |")
            else:
                line += " — | — | — |"
        lines.append(line)
    return "\n".join(lines)


def plot_time_vs_error(rows, path, have_gpu):
    backends = [b for b in ("cpu", "gpu") if b == "cpu" or have_gpu]
    fig, axes = plt.subplots(1, len(backends), figsize=(6.5 * len(backends), 5), squeeze=False)
    for ax, backend in zip(axes[0], backends):
        shown = [r for r in rows
                 if r["scene"] == "dragon" and backend in r and r["precision"] == "float"]
        for i, r in enumerate(shown):
            x, y = r[backend]["ms"], max(r[backend]["rmse"], 1e-6)
            ax.scatter(x, y, s=25)
            # Alternate label offsets: settings of equal error sit side by side.
            ax.annotate(r["name"], (x, y), fontsize=7, xytext=(4, 4 - 12 * (i % 2)),
                        textcoords="offset points")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(f"{backend.upper()} time per frame (ms, log)")
        ax.set_ylabel("RMSE against the double reference (log)")
        ax.set_title(f"Dragon scene: time against error ({backend.upper()})")
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_knobs(rows, path):
    """PSNR and outlier share of every float setting, one bar each, grouped by scene."""
    shown = [r for r in rows if r["precision"] == "float"]
    labels = [f"{r['scene']}: {r['name']}" for r in shown]
    psnr = [min((r.get("cpu") or r["gpu"]).get("psnr_db") or 120.0, 120.0) for r in shown]
    outliers = [100 * (r.get("cpu") or r["gpu"])["outlier_rate"] for r in shown]
    fig, (ax_p, ax_o) = plt.subplots(1, 2, figsize=(13, 0.32 * len(shown) + 1.5), sharey=True)
    ys = range(len(shown))
    ax_p.barh(ys, psnr, color="tab:blue")
    ax_p.set_yticks(list(ys), labels, fontsize=8)
    ax_p.invert_yaxis()
    ax_p.set_xlabel("PSNR against the reference (dB, higher is better)")
    ax_o.barh(ys, outliers, color="tab:red")
    ax_o.set_xlabel("outlier pixels (%): a channel off by more than 0.1")
    for ax in (ax_p, ax_o):
        ax.grid(True, axis="x", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def stem(scene, name, backend):
    return f"{scene}_{backend}_" + "".join(c if c.isalnum() else "_" for c in name)


def find_image(folder, base):
    for ext in (".png", ".ppm"):
        if os.path.exists(os.path.join(folder, base + ext)):
            return os.path.join(folder, base + ext)
    return None


def plot_error_images(folder, path):
    pictures = [("dragon reference", find_image(folder, "dragon_reference")),
                ("spheres reference", find_image(folder, "spheres_reference"))]
    for scene, name in ERROR_PICTURES:
        pictures.append((f"{scene}: {name} (|diff| x4)",
                         find_image(folder, stem(scene, name, "cpu"))))
    pictures = [(t, p) for t, p in pictures if p]
    if not pictures:
        return False
    cols = 3
    rows = (len(pictures) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(3.4 * cols, 2.2 * rows), squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for ax, (title, p) in zip(axes.flat, pictures):
        ax.imshow(mpimg.imread(p))
        ax.set_title(title, fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return True


def machine_line(name, report):
    m = report["machine"]
    where = m.get("gpu") or f"{m['cpu']}, {m['threads']} threads"
    return (f"- `{name}`: {report['backend']} back end, {where}, {report['size']}, "
            f"{m['date']}, commit {m['commit']}")


def row_of(rows, scene, name):
    return next((r for r in rows if r["scene"] == scene and r["name"] == name), None)


def errors_of(row):
    return row.get("cpu") or row.get("gpu")


def findings(rows):
    """Sentences with this run's numbers, for the knobs the scenes were built to show."""
    out = []

    def get(scene, name):
        r = row_of(rows, scene, name)
        return (r, errors_of(r)) if r else (None, None)

    r, e = get("dragon", "base: float")
    if r:
        out.append(f"- **float vs double**: the base setting in float differs from the double "
                   f"reference by RMSE {e['rmse']:.5f} ({psnr_text(e)} dB). Its "
                   f"{100 * e['outlier_rate']:.3f}% outlier pixels lie where a surface comes "
                   f"within a few hundredths of the ground: under the glass sphere and at the "
                   f"dragon's lowest points. The watertight test drops hits nearer than its "
                   f"bound on the error of t, and that bound grows with the triangle's "
                   f"coordinates: for the ground's 10^5 vertices it is 0.02-0.05, so a ray "
                   f"leaving the sphere's underside toward the ground 0.02 away passes through "
                   f"it (float only; the double bound is ~10^-11).")
    r, e = get("dragon", "float only (no double near hits)")
    _, base = get("dragon", "base: float")
    if r and base:
        out.append(f"- **near hits**: the renderers decide a hit nearer than the watertight "
                   f"test's bound again on the triangle's plane in double (issue 12, "
                   f"docs/robustness.md), so the ground under the sphere is not passed "
                   f"through; deciding them in float only, as before, gives RMSE "
                   f"{e['rmse']:.5f} and {100 * e['outlier_rate']:.3f}% outlier pixels "
                   f"against the base's {base['rmse']:.5f} and "
                   f"{100 * base['outlier_rate']:.3f}%.")
    r, e = get("dragon", "Moller-Trumbore + fixed epsilon")
    _, e2 = get("dragon", "fixed epsilon 1e-4")
    if r and e2:
        out.append(f"- **ray offset**: a fixed 1e-4 offset alone leaves the dragon scene as it was "
                   f"(outliers {100 * e2['outlier_rate']:.3f}%): the watertight test rejects hits "
                   f"closer than its own error bound on t, which catches the self-hits. With "
                   f"Moller-Trumbore (which accepts any t > 0) the far ground shows acne: "
                   f"{100 * e['outlier_rate']:.1f}% outlier pixels, RMSE {e['rmse']:.4f}.")
    r, e = get("dragon", "Moller-Trumbore")
    if r:
        out.append(f"- **triangle test**: Moller-Trumbore alone changes "
                   f"{100 * e['mismatch_rate']:.3f}% of the primary hits (rays through shared "
                   f"edges are rare in an image; tests/bench/accuracy_variants_test.cpp shows them deterministically).")
    r, e = get("spheres", "naive quadratic")
    if r:
        out.append(f"- **sphere test**: the textbook quadratic loses the far spheres' silhouettes: "
                   f"{100 * e['mismatch_rate']:.2f}% of primary hits change, "
                   f"{100 * e['outlier_rate']:.2f}% outlier pixels; the RTG ch. 7 form in float "
                   f"matches the double reference. On the dragon scene's near glass sphere both "
                   f"forms agree.")
    r, e = get("spheres", "fixed epsilon 1e-4")
    if r:
        out.append(f"- **fixed epsilon on spheres**: the sphere test has no bound on t, so at "
                   f"4000 from the origin a 1e-4 offset shows acne on its own: "
                   f"{100 * e['outlier_rate']:.2f}% outlier pixels.")
    depth = [r for r in rows if r["knob"] == "max depth"]
    if depth:
        parts = ", ".join(f"{r['max_depth']}: {psnr_text(errors_of(r))} dB" for r in depth)
        out.append(f"- **max depth** (PSNR by depth; the base is 8): {parts}. Depth 3 is the "
                   f"least that lets light through the glass sphere (in, out, background).")
    spp = [r for r in rows if r["knob"] == "samples per pixel"]
    if spp:
        parts = ", ".join(f"{r['spp']}: {psnr_text(errors_of(r))} dB" for r in spp)
        out.append(f"- **samples per pixel** (PSNR against the 16-sample reference): {parts}.")
    builders = [r for r in rows if r["knob"] == "BLAS builder"]
    base = row_of(rows, "dragon", "base: float")
    if builders and base and "cpu" in base:
        parts = ", ".join(f"{r['builder']} {r['cpu']['ms']:.0f} ms (RMSE {r['cpu']['rmse']:.5f})"
                          for r in builders if "cpu" in r)
        out.append(f"- **BLAS builder**: the image does not depend on the tree (binned "
                   f"{base['cpu']['ms']:.0f} ms, {parts}); only time can, and on the 2-core VM "
                   f"frame times vary by 10-20% from run to run, more than the builders differ "
                   f"here (bench cpu measures them on the paper scene).")
    refits = [r for r in rows if r["knob"] == "TLAS update"]
    b = row_of(rows, "spheres", "base: float")
    if refits and b:
        def times(r):
            return " / ".join(f"{r[k]['ms']:.1f}" for k in ("cpu", "gpu") if k in r)
        parts = ", ".join(f"{r['name']}: {times(r)} ms, RMSE {errors_of(r)['rmse']:.5f}"
                          for r in refits)
        backends = " / ".join(k.upper() for k in ("cpu", "gpu") if k in b)
        out.append(f"- **TLAS update**: refit boxes are conservative, so a refit TLAS gives the "
                   f"image of a built one (base, SAH TLAS: {times(b)} ms ({backends}), RMSE "
                   f"{errors_of(b)['rmse']:.5f}); the interval can cost only time: {parts}. "
                   f"With 28 instances the worst tree costs at most a test of every sphere per "
                   f"ray, so the slowdown is bounded (bench grid shows TLAS costs at scale).")
    return "\n".join(out)


INTRO = """# Accuracy against time

`rtrt bench accuracy` sweeps the knobs that trade accuracy for time, one at a time away from a
base setting, times each setting on the CPU and/or the GPU, and compares its image with a
high-accuracy reference. This page is generated: `tools/accuracy_report.py` writes it and its
plots from the benchmark's JSON results (see "Regenerating" below); do not edit it by hand.

## Settings

- **Base**: float, watertight triangle test (Woop, Benthin, Wald 2013), ray origins offset by
  error bounds (pbrt-v4 6.8), Ray Tracing Gems ch. 7 sphere test, 16 samples per pixel (4 x 4
  strata, one jittered sample each, the same positions on every run and back end), max depth 8,
  binned-SAH BLAS, SAH TLAS built over the instances.
- **Reference**: the base setting computed in double precision on the CPU
  (`bench/accuracy/reference_*.h`): camera rays, instance transforms (the stored float
  world-to-object matrix, which the renderers apply, taken as exact and inverted in double for
  the object-to-world one), triangle and sphere tests,
  hit points, error bounds, offsets and shading are doubles; the scene data stays as the float
  renderer sees it (float vertices, spheres, transforms, BVH boxes), over the sweep-SAH BLAS.
  The float boxes are widened by 8 float ulps of their magnitude and the double slab interval by
  1 + 2 gamma(3), so traversal never culls a primitive the ray meets.
- **Knobs**, each row changes one: max depth 1-4; 1, 4 or 9 samples per pixel; Moller-Trumbore
  (1997, any t > 0 accepted) instead of watertight; a fixed 1e-4 offset along the normal instead
  of error bounds (alone and with Moller-Trumbore); the textbook sphere quadratic
  (b^2 - ac) instead of the RTG form; sweep-SAH or centroid-split BLAS instead of binned SAH; the
  runtime's TLAS (`DynamicTlas`, an LBVH) rebuilt, or refit 10, 100 or 1000 frames after it was
  built, instead of the SAH TLAS built for where the instances are (spheres scene: each sphere
  moved 0.2 per frame since the build, sphere i in the direction (cos 2.39996 i, sin 2.39996 i,
  0); a runtime that rebuilds every N frames traces such a tree just before each rebuild); float instead of double (the base row); near hits decided in float only, without the
  double test on the triangle's plane (the "float only" rows). The
  "textbook" row turns on all three less robust tests with 1 sample and depth 4.

The test variants are trace policies (`AccuracyPolicy<bits>` in `bench/accuracy/accuracy_policy.h`,
beside production's `TracePolicy` in `engine/render_rt/trace_policy.h`): each bit swaps one step,
the triangle test, the sphere test or the ray offset, inside the policy function of that step.
They are instantiated only in the benchmark's own translation units
(`bench/accuracy/accuracy_cpu.cpp`, `accuracy_cuda.cu`), for the one feature set of its scenes,
through production's CPU tile loop (`engine/render_rt/cpu/trace_tiles.h`) and production's CUDA
kernel, launch and timing loop (`engine/render_rt/cuda/trace_launch.cuh`), in the traversal form
the scene's instance count selects (on the GPU, the single two-level loop from 64 instances); the
default kernels are unchanged.

## Scenes

- **dragon**: the README's paper scene (the full 871,414-triangle dragon fitted to extent 5 and
  centred, camera at (0,0,10) looking down -z, 45 degree vertical FOV, red reflective material,
  one directional light toward normalize(1,1,1) with shadows, background (0.2,0.3,0.5)) plus a
  ground of two triangles with corners at x, z = +-10^5 on the plane
  y = y0 + 0.05 x - 0.1 z, y0 0.01 below the dragon's lowest point (grey: diffuse 0.6,
  ambient 0.06, specular 0.2 exponent 16, reflectivity 0.2), and a glass sphere of radius 1.2
  standing on the ground at x = 3.6, z = 1.5 (transmissivity 0.95, ior 1.5, specular 0.8
  exponent 128). The ground's vertices lie 10^5 from the origin, so its interpolated hit points
  err by ~10^-2 per coordinate and, the plane being tilted, ~10^-3 along its normal: ten times a
  fixed 10^-4 offset.
- **spheres**: 7 x 4 instances of one sphere of radius 1.5 on a 4-unit grid centred on
  (0, 0, -4000), each with its own colour (diffuse (0.2 + 0.1 col, 0.6, 0.2 + 0.2 row), ambient
  0.1 x diffuse, specular 0.4, reflectivity 0.2); camera at the origin looking down -z with a
  0.3 degree vertical FOV; one directional light toward normalize(1,1,1); background as above.
  Distance over radius is ~2700: the textbook quadratic subtracts two numbers of ~1.6 x 10^7 to
  find a difference of at most r^2 = 2.25, and loses it.

## Measures

Colours are clamped to [0, 1] (as displayed) before they are compared with the reference of
the same scene and size; a channel that is NaN in either image differs by 1, the most a displayed
channel can (so a NaN pixel is an outlier, never a match).
- **RMSE**: root mean square of the differences over every channel of every pixel.
- **PSNR**: 20 log10(1 / RMSE) dB (peak 1); ∞ for identical images.
- **outliers**: the share of pixels with some channel more than 0.1 from the reference: acne,
  leaks, missing or extra objects, as opposed to rounding noise.
- **mismatch (miss rate)**: the share of pixels whose primary ray through the pixel centre hits
  a different object than the reference's (a miss counts as object 0; an object is an
  instance). It measures the intersection and traversal knobs only: samples per pixel and depth
  do not change it.
- **time**: CPU, the wall clock of the whole frame, one warm-up frame, median of
  `--cpu-frames` (5); GPU, CUDA events around the trace kernel, 5 warm-up launches, median of
  `--gpu-frames` (20; of an even count, the upper of the middle two). The reference's CPU time is
  that of one double-precision frame. The development VM's 2 cores are shared: there, CPU times
  of the same setting varied by up to 2x between runs (base float: 1363 to 2688 ms in five
  runs on 2026-11-29 with the same trace code, the slow ones beside another engineer's builds), while every error measure came out
  identical (the renders are deterministic). Compare CPU times within one run, and with care.
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("paths", nargs="+", help="RESULT.json ... DOCS_DIR")
    parser.add_argument("--images", help="folder of `rtrt bench accuracy --images`")
    args = parser.parse_args()
    if len(args.paths) < 2:
        parser.error("need at least one RESULT.json and the DOCS_DIR")
    *sources, docs = args.paths
    runs = load(sources)
    rows = merge(runs)
    have_gpu = any("gpu" in r for r in rows)
    image_dir = os.path.join(docs, "images")
    os.makedirs(image_dir, exist_ok=True)
    plot_time_vs_error(rows, os.path.join(image_dir, "accuracy_time_vs_error.png"), have_gpu)
    plot_knobs(rows, os.path.join(image_dir, "accuracy_knobs.png"))
    if args.images:
        plot_error_images(args.images, os.path.join(image_dir, "accuracy_errors.png"))
    sources_md = "\n".join(machine_line(n, r) for n, r in runs)
    command = "tools/accuracy_report.py " + " ".join(
        os.path.join("bench/results", n) for n, _ in runs) + " docs/"
    gpu_note = "" if have_gpu else (
        "\nNo GPU result yet: run `rtrt bench accuracy --backend cuda` on the GPU machine "
        "(tools/device/round.sh does) and regenerate with both files.\n")
    parts = [INTRO, "## Results\n", "Runs:\n", sources_md, gpu_note,
             "\n![time against error](images/accuracy_time_vs_error.png)\n",
             "![PSNR and outliers per setting](images/accuracy_knobs.png)\n",
             table(rows, have_gpu),
             "\nRMSE, PSNR, outliers and mismatch are the CPU run's where there is one; the GPU "
             "columns are the GPU run's own, against the reference rendered at its size on its "
             "host.\n",
             "\nWhat the numbers say:\n", findings(rows)]
    if os.path.exists(os.path.join(image_dir, "accuracy_errors.png")):
        parts.append("\nReferences and where settings differ from them (|difference| x 4; CPU "
                     "run):\n\n![difference images](images/accuracy_errors.png)\n")
    parts.append(f"""
## Regenerating

```
build/release/game/rtrt bench accuracy --backend cpu -o bench/results/accuracy-cpu-DATE.json \\
    --images /tmp/accuracy-images
build/gpu/game/rtrt bench accuracy --backend cuda -o accuracy-gpu.json  # GPU machine (round.sh)
{command} --images /tmp/accuracy-images
```
The CPU run defaults to 480x270 and the CUDA run to 1280x720 (`--size` sets both); each run
renders its own reference on its machine's CPU at its size.
""")
    with open(os.path.join(docs, "accuracy.md"), "w") as f:
        f.write("\n".join(parts))
    print(f"wrote {os.path.join(docs, 'accuracy.md')} and {image_dir}/accuracy_*.png")


if __name__ == "__main__":
    main()
