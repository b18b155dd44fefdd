#!/usr/bin/env python3
"""`rtrt farm` on a real Slurm: a one-host cluster (munge, slurmctld, slurmd on localhost, from
Debian's packages, brought up by tools/slurm_cluster.sh in WORK_DIR) runs

1. a 4-shard job of a 48-frame demo_physics at 320x180: every frame equals a single-process
   `play --headless` run's byte for byte, the manifest vouches for each, and the MP4 has 48 frames
   of 320x180 (ffprobe);
2. a job whose running task has its rtrt process killed: the task requeues itself and the job
   completes with identical frames;
3. a job one of whose array elements is cancelled (scancel): the assembly never runs, --status
   says what is missing, and rerunning the same command renders only that and completes.

Where Slurm cannot start (no packages, not root, a daemon that dies) it prints why and exits 77,
which ctest reports as skipped.

usage: slurm_farm_test.py RTRT SOURCE_DIR WORK_DIR FORMAT
"""
import filecmp
import glob
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

RTRT, SOURCE, WORK, FORMAT = sys.argv[1:5]
# The cluster's own folder is short: Slurm's socket paths inside it must stay under 108 bytes.
CLUSTER = tempfile.mkdtemp(prefix="rtrt-slurm-")
SCENE, SIZE, FRAMES, SHARDS = "demo_physics", "320x180", 48, 4
SKIP = 77
ENV = dict(os.environ)


def fail(what):
    sys.exit("FAIL: " + what)


def check(condition, what):
    if not condition:
        fail(what)
    print("ok:", what, flush=True)


def run(args, expect=0, timeout=600):
    p = subprocess.run(args, capture_output=True, text=True, env=ENV, timeout=timeout)
    if expect is not None and p.returncode != expect:
        fail(f"{' '.join(args)}: exit {p.returncode}, expected {expect}\n{p.stdout}\n{p.stderr}")
    return p


def farm_args(folder, spp):
    return [RTRT, "farm", SCENE, "--frames", f"0:{FRAMES}", "--shards", str(SHARDS), "--size",
            SIZE, "--spp", str(spp), "--backend", "cpu", "--format", FORMAT, "-o", folder]


def reference(spp):
    folder = os.path.join(WORK, f"reference_spp{spp}")
    os.makedirs(folder, exist_ok=True)
    run([RTRT, "play", SCENE, "--headless", "--frames", str(FRAMES), "--size", SIZE, "--spp",
         str(spp), "--backend", "cpu", "-o", os.path.join(folder, f"frame_%06d.{FORMAT}")])
    return folder


def frame_file(folder, i):
    return os.path.join(folder, "frames", f"frame_{i:06d}.{FORMAT}")


def queued(name_part):
    """Jobs of ours still in squeue: (jobid, state) pairs."""
    out = run(["squeue", "-h", "-o", "%i %T %j"], expect=None).stdout
    return [tuple(line.split()[:2]) for line in out.splitlines() if name_part in line]


def wait_for(predicate, what, timeout):
    start = time.time()
    while time.time() - start < timeout:
        if predicate():
            return time.time() - start
        time.sleep(0.5)
    fail(f"timed out after {timeout} s waiting for {what}; squeue:\n"
         + run(["squeue"], expect=None).stdout)


def status(folder):
    return run([RTRT, "farm", "--status", folder], expect=None)


def same_frames(folder, ref):
    different = [i for i in range(FRAMES)
                 if not filecmp.cmp(frame_file(folder, i),
                                    os.path.join(ref, f"frame_{i:06d}.{FORMAT}"), shallow=False)]
    check(not different, f"{folder}: all {FRAMES} frames equal play --headless's byte for byte"
          + (f" (not {different})" if different else ""))


def check_video(folder):
    probe = run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0",
                 "-show_entries", "stream=codec_name,width,height,nb_read_frames", "-of",
                 "csv=p=0", os.path.join(folder, "video.mp4")]).stdout.strip()
    check(probe == f"h264,320,180,{FRAMES}", f"video.mp4: H.264 320x180, {FRAMES} frames ({probe})")
    check(os.path.getsize(os.path.join(folder, "contact_sheet.png")) > 0, "contact sheet written")


def manifest_entries(folder):
    entries = {}
    for path in glob.glob(os.path.join(folder, "manifest", "*.tsv")):
        with open(path) as f:
            for line in f:
                frame, name, size, digest = line.rstrip("\n").split("\t")
                entries[int(frame)] = (name, int(size), digest)
    return entries


def running_task_pid(folder):
    """The pid of an rtrt play process rendering into FOLDER, or None."""
    out = subprocess.run(["pgrep", "-f", f"{RTRT} play .* {folder}/frames"], capture_output=True,
                         text=True).stdout.split()
    return int(out[0]) if out else None


def plain_submission(folder, spp):
    out = run(farm_args(folder, spp)).stdout
    m = re.search(r"submitted render job (\d+) \((\d+) tasks\) and assemble job (\d+)", out)
    check(m is not None, f"farm submitted a render array and an assembly ({out.strip()})")
    return m.group(1), int(m.group(2)), m.group(3)


def test_job(ref):
    folder = os.path.join(WORK, "job_plain")
    start = time.time()
    render, tasks, _ = plain_submission(folder, 1)
    check(tasks == SHARDS, f"{SHARDS} array tasks")
    wait_for(lambda: status(folder).returncode == 0, "the plain job", 600)
    print(f"plain job done in {time.time() - start:.1f} s", flush=True)
    same_frames(folder, ref)
    entries = manifest_entries(folder)
    check(sorted(entries) == list(range(FRAMES)), "the manifest lists every frame")
    bad = [i for i, (name, size, _) in entries.items()
           if name != os.path.basename(frame_file(folder, i))
           or os.path.getsize(frame_file(folder, i)) != size]
    check(not bad, "manifest names and sizes match the files (status checked the checksums)")
    files = sorted(os.path.basename(p) for p in glob.glob(os.path.join(folder, "manifest", "*")))
    check(files == [f"render-{render}_{i}.tsv" for i in range(SHARDS)],
          "one manifest per array element")
    check_video(folder)


def test_killed_task(ref):
    folder = os.path.join(WORK, "job_killed")
    render, _, _ = plain_submission(folder, 16)
    # Kill the first task's rtrt once it has finished a frame.
    wait_for(lambda: running_task_pid(folder) and glob.glob(os.path.join(folder, "frames", "*")),
             "a task rendering", 300)
    pid = running_task_pid(folder)
    os.kill(pid, signal.SIGKILL)
    print(f"killed rtrt process {pid}", flush=True)
    wait_for(lambda: status(folder).returncode == 0, "the job with a killed task", 900)
    logs = "".join(open(p).read() for p in glob.glob(os.path.join(folder, "logs", "render-*")))
    check("requeueing it" in logs, "the task whose process was killed requeued itself")
    same_frames(folder, ref)
    check_video(folder)


def test_cancelled_element(ref):
    folder = os.path.join(WORK, "job_cancelled")
    render, _, assemble = plain_submission(folder, 16)
    # Cancel element 2 once it has written its first frame: a cancel that lands while Slurm is
    # still launching a --requeue batch job (already RUNNING in squeue) can requeue it instead,
    # and the element then renders everything.
    first = 2 * FRAMES // SHARDS
    wait_for(lambda: (render + "_2", "RUNNING") in queued("rtrt-render")
             and os.path.exists(frame_file(folder, first)), "element 2 rendering", 300)
    run(["scancel", f"{render}_2"])
    wait_for(lambda: not queued("rtrt-"), "the queue to empty after the scancel", 900)
    st = status(folder)
    check(st.returncode == 3 and "missing" in st.stdout and "not made yet" in st.stdout,
          "status after the scancel: frames missing, no video, exit 3")
    missing = int(re.search(r"(\d+) missing", st.stdout).group(1))
    done_before = manifest_entries(folder)
    kept = {i: os.stat(frame_file(folder, i)).st_mtime_ns for i in done_before}
    out = run(farm_args(folder, 16)).stdout
    check(f"{missing} missing" in out, f"the rerun finds the {missing} missing frames")
    wait_for(lambda: status(folder).returncode == 0, "the resumed job", 900)
    rewritten = [i for i, t in kept.items() if os.stat(frame_file(folder, i)).st_mtime_ns != t]
    check(not rewritten, f"the rerun rendered only the missing frames (rewrote {rewritten})")
    same_frames(folder, ref)
    check_video(folder)


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    up = subprocess.run([os.path.join(SOURCE, "tools", "slurm_cluster.sh"), "up", CLUSTER],
                        capture_output=True, text=True)
    if up.returncode == 3:
        print("SKIP: " + up.stderr.strip())
        shutil.rmtree(CLUSTER, ignore_errors=True)
        sys.exit(SKIP)
    if up.returncode != 0:
        fail(f"slurm_cluster.sh up: exit {up.returncode}\n{up.stdout}\n{up.stderr}")
    ENV["SLURM_CONF"] = re.search(r"export SLURM_CONF=(\S+)", up.stdout).group(1)
    try:
        ref1, ref16 = reference(1), reference(16)
        test_job(ref1)
        test_killed_task(ref16)
        test_cancelled_element(ref16)
    finally:
        subprocess.run([os.path.join(SOURCE, "tools", "slurm_cluster.sh"), "down", CLUSTER])
        shutil.rmtree(CLUSTER, ignore_errors=True)
    print("slurm_farm: all checks passed")


if __name__ == "__main__":
    main()
