#!/usr/bin/env python3
"""A full disk under render, play --headless, convert, bench deform and the BLAS cache.

Each failed write must exit 1 with "rtrt: error: FILE: No space left on device" (FILE the output
the user named) and leave nothing behind: no output, no temporary. A failed BLAS cache write must
not fail the render: one warning, and no file in the cache.

The full disk is a real one where a tmpfs can be mounted (root, a container that allows it), and
always also an injected one: RTRT_TEST_FAIL_WRITE_AFTER makes writes past the first bytes of each
output fail with ENOSPC (the image of the BLAS cache case is smaller than that, so it succeeds).

usage: disk_full_test.py RTRT WORK_DIR
"""
import os
import shutil
import subprocess
import sys

RTRT, WORK = sys.argv[1], sys.argv[2]
FREE_BYTES = 8192  # less than any output below, so each fails part-way
REASON = "No space left on device"


def write_grid_mesh(path, n=80):
    with open(path, "w") as f:
        for y in range(n + 1):
            for x in range(n + 1):
                f.write(f"v {x / n - 0.5} {y / n - 0.5} -2\n")
        for y in range(n):
            for x in range(n):
                a = y * (n + 1) + x + 1
                f.write(f"f {a} {a + 1} {a + n + 2}\nf {a} {a + n + 2} {a + n + 1}\n")


def run(args, env_extra):
    env = dict(os.environ, RTRT_CACHE_DIR="off")
    env.update(env_extra)
    return subprocess.run([RTRT] + args, capture_output=True, text=True, env=env, timeout=120)


def leftovers(folder, keep):
    return sorted(set(os.listdir(folder)) - set(keep))


def expect_write_failure(name, args, output, folder, keep, env, then=""):
    r = run(args, env)
    expected = f"rtrt: error: {output}: {REASON}{then}"
    if r.returncode != 1 or expected not in r.stderr:
        sys.exit(f"{name}: status {r.returncode}, expected 1 and \"{expected}\":\n{r.stderr}")
    if leftovers(folder, keep):
        sys.exit(f"{name}: left {leftovers(folder, keep)} in {folder}")
    print(f"{name}: ok ({r.stderr.strip()})")


def check_all(mechanism, full, env, scratch):
    """FULL: the folder on the full disk; SCRATCH: a folder with room."""
    keep = os.listdir(full)
    for ext in (".png", ".ppm", ".exr"):
        out = os.path.join(full, "out" + ext)
        expect_write_failure(f"{mechanism} render {ext}",
                             ["render", "default", "--size", "160x120", "-o", out],
                             out, full, keep, env)
    pattern = os.path.join(full, "f_%02d.ppm")
    expect_write_failure(f"{mechanism} play --headless",
                         ["play", os.path.join(WORK, "grid.json"), "--headless", "--frames", "3",
                          "--size", "160x120", "-o", pattern],
                         os.path.join(full, "f_00.ppm"), full, keep, env,
                         "; no frame was written, and --frames 0:3 goes on from here")
    out = os.path.join(full, "grid.rtmodel")
    expect_write_failure(f"{mechanism} convert", ["convert", os.path.join(WORK, "grid.obj"),
                                                  "-o", out], out, full, keep, env)
    # A benchmark's two outputs: the CSV fails, and the JSON, finished first, is not left alone
    # (it had been in place).
    report, table = os.path.join(full, "deform.json"), os.path.join(full, "deform.csv")
    expect_write_failure(f"{mechanism} bench deform",
                         ["bench", "deform", os.path.join(WORK, "wave.json"), "--backend", "cpu",
                          "--size", "4x4", "--frames", "150", "--samples", "2", "-o", report,
                          "--csv", table], table, full, keep, env)
    # The BLAS cache on the full disk, the image where there is room: the render succeeds.
    cache = os.path.join(full, "cache")
    image = os.path.join(scratch, "cached.ppm")
    r = run(["render", os.path.join(WORK, "grid.json"), "--size", "32x24", "-o", image],
            dict(env, RTRT_CACHE_DIR=cache))
    warnings = r.stderr.count("warning: BLAS cache not written")
    if r.returncode != 0 or warnings != 1 or REASON not in r.stderr or not os.path.exists(image):
        sys.exit(f"{mechanism} BLAS cache: status {r.returncode}, {warnings} warnings:\n{r.stderr}")
    cached = os.listdir(cache) if os.path.isdir(cache) else []
    if cached:
        sys.exit(f"{mechanism} BLAS cache: left {cached} in {cache}")
    shutil.rmtree(cache, ignore_errors=True)
    os.remove(image)
    print(f"{mechanism} BLAS cache: ok ({r.stderr.strip()})")


def fill(folder):
    """Fills FOLDER's filesystem, then frees FREE_BYTES."""
    filler = os.path.join(folder, "filler")
    fd = os.open(filler, os.O_WRONLY | os.O_CREAT)
    try:
        while True:
            os.write(fd, b"\0" * 4096)
    except OSError:
        pass
    os.close(fd)
    os.truncate(filler, max(0, os.path.getsize(filler) - FREE_BYTES))


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    write_grid_mesh(os.path.join(WORK, "grid.obj"))
    with open(os.path.join(WORK, "grid.json"), "w") as f:
        f.write('{ "models": { "m": { "type": "mesh", "file": "grid.obj" } },'
                ' "instances": [ { "model": "m" } ] }')
    with open(os.path.join(WORK, "wave.json"), "w") as f:
        f.write('{ "models": { "m": { "type": "mesh", "file": "grid.obj" } },'
                ' "instances": [ { "model": "m", "deform": { "wave": { "amplitude": 0.05,'
                ' "wavelength": 0.5 } } } ] }')
    scratch = os.path.join(WORK, "scratch")
    os.makedirs(scratch)

    mount = os.path.join(WORK, "tmpfs")
    os.makedirs(mount)
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "tmpfs", mount],
                             capture_output=True).returncode == 0
    if mounted:
        try:
            fill(mount)
            check_all("tmpfs", mount, {}, scratch)
        finally:
            subprocess.run(["umount", mount])
    else:
        print("a tmpfs cannot be mounted here: the injected failure alone is tested")

    injected = os.path.join(WORK, "injected")
    os.makedirs(injected)
    check_all("injected", injected, {"RTRT_TEST_FAIL_WRITE_AFTER": str(FREE_BYTES)}, scratch)
    print("full disk tested with " + ("a tmpfs and " if mounted else "") + "an injected failure")


main()
