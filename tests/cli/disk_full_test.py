#!/usr/bin/env python3
"""A full disk under render, play --headless, convert, bench deform and the BLAS cache, and
play's later frames whose paths cannot be written.

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


def check_manifest_failure(full, scratch):
    """The manifest on the full disk, frames where there is room: frame 0 is written before its
    line fails, and the message says so."""
    frames = os.path.join(scratch, "manifest")
    os.makedirs(frames)
    manifest = os.path.join(full, "frames.tsv")
    fill(full, "filler_all", 0)
    r = run(["play", os.path.join(WORK, "grid.json"), "--headless", "--frames", "3", "--size",
             "160x120", "-o", os.path.join(frames, "f_%02d.ppm"), "--manifest", manifest], {})
    expected = (f"rtrt: error: {manifest}: {REASON}; frame 0 is written and kept (frame 0 is not "
                "in the manifest), and --frames 0:3 goes on from here")
    if r.returncode != 1 or expected not in r.stderr or os.listdir(frames) != ["f_00.ppm"]:
        sys.exit(f"tmpfs manifest: status {r.returncode}, files {os.listdir(frames)}, expected 1 "
                 f"and \"{expected}\":\n{r.stderr}")
    # The manifest its first line was to begin is not left behind empty.
    if os.path.exists(manifest):
        sys.exit(f"tmpfs manifest: {manifest} left behind ({os.path.getsize(manifest)} bytes)")
    shutil.rmtree(frames)
    print(f"tmpfs manifest: ok ({r.stderr.strip()})")


def check_farm_start(full):
    """farm --local whose farm.json cannot be written: nothing started, the folder it made is
    gone (its lock file had stayed), and the message says what to do."""
    job = os.path.join(full, "job")
    r = run(["farm", os.path.join(WORK, "grid.json"), "--frames", "0:2", "--size", "32x24",
             "--local", "-o", job], {})
    if r.returncode != 1 or "nothing was started: rerun this command once that is fixed" not in r.stderr or os.path.exists(job):
        sys.exit(f"tmpfs farm start: status {r.returncode}, folder left: {os.path.exists(job)}:"
                 f"\n{r.stderr}")
    print(f"tmpfs farm start: ok ({r.stderr.strip()})")


def check_later_frames(scratch):
    """A later frame's path that cannot be written: the last frame's name is checked before the
    work (exit 2, nothing written); a folder in a frame's place is found when the frame is due,
    and the run stops as a failed write does (exit 1, the frames before kept, the command that
    goes on)."""
    folder = os.path.join(scratch, "later")
    os.makedirs(os.path.join(folder, "f_02.ppm"))
    r = run(["play", os.path.join(WORK, "grid.json"), "--headless", "--frames", "4", "--size",
             "32x24", "-o", os.path.join(folder, "f_%02d.ppm")], {})
    expected = "; frames 0 to 1 are written and kept, and --frames 2:4 goes on from here"
    if r.returncode != 1 or expected not in r.stderr or \
            sorted(os.listdir(folder)) != ["f_00.ppm", "f_01.ppm", "f_02.ppm"]:
        sys.exit(f"later folder: status {r.returncode}, files {sorted(os.listdir(folder))}, "
                 f"expected 1 and \"{expected}\":\n{r.stderr}")
    print(f"later folder: ok ({r.stderr.strip()})")
    # A later frame's name that is a link to an earlier frame of the run: it would replace it.
    linked = os.path.join(scratch, "linked")
    os.makedirs(linked)
    os.symlink("f_00.ppm", os.path.join(linked, "f_02.ppm"))
    r = run(["play", os.path.join(WORK, "grid.json"), "--headless", "--frames", "3", "--size",
             "32x24", "-o", os.path.join(linked, "f_%02d.ppm")], {})
    expected = "leads to frame 0, written by this run (a link?); remove it; frames 0 to 1 are"
    if r.returncode != 1 or expected not in r.stderr:
        sys.exit(f"later link: status {r.returncode}, expected 1 and \"{expected}\":\n{r.stderr}")
    print(f"later link: ok ({r.stderr.strip()[-160:]})")
    # Frame 9's name has 255 bytes, frame 10's one more.
    long = os.path.join(folder, "n" * 250 + "%d.ppm")
    r = run(["play", os.path.join(WORK, "grid.json"), "--headless", "--frames", "9:11", "--size",
             "32x24", "-o", long], {})
    if r.returncode != 2 or "10.ppm" not in r.stderr or \
            any(name.startswith("n") for name in os.listdir(folder)):
        sys.exit(f"later long name: status {r.returncode}, expected 2 before any frame:\n"
                 f"{r.stderr}")
    print(f"later long name: ok ({r.stderr.strip()[:120]}...)")
    shutil.rmtree(folder)


def fill(folder, name="filler", free=FREE_BYTES):
    """Fills FOLDER's filesystem, then frees FREE bytes."""
    filler = os.path.join(folder, name)
    fd = os.open(filler, os.O_WRONLY | os.O_CREAT)
    try:
        while True:
            os.write(fd, b"\0" * 4096)
    except OSError:
        pass
    os.close(fd)
    os.truncate(filler, max(0, os.path.getsize(filler) - free))


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
            check_manifest_failure(mount, scratch)
            if shutil.which("ffmpeg"):  # farm --local refuses to start without it
                check_farm_start(mount)
        finally:
            subprocess.run(["umount", mount])
    else:
        print("a tmpfs cannot be mounted here: the injected failure alone is tested")

    check_later_frames(scratch)
    injected = os.path.join(WORK, "injected")
    os.makedirs(injected)
    check_all("injected", injected, {"RTRT_TEST_FAIL_WRITE_AFTER": str(FREE_BYTES)}, scratch)
    print("full disk tested with " + ("a tmpfs and " if mounted else "") + "an injected failure")


main()
