#!/usr/bin/env python3
"""`rtrt farm` without a cluster: the dry run's scripts, the message where Slurm is missing,
--local renders that equal `rtrt play --headless` byte for byte, a resume that renders only the
missing and corrupt frames, --status's exit statuses, a folder of other settings (or of no job)
refused and left as it was, options of two modes refused, a task that ends with its farm, and
a Slurm whose squeue cannot say what is queued (refused, not submitted twice).

usage: farm_cli_test.py RTRT WORK_DIR FORMAT   (FORMAT: png, or ppm where rtrt has no PNG)
"""
import ctypes
import fcntl
import filecmp
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import time

RTRT, WORK, FORMAT = sys.argv[1], sys.argv[2], sys.argv[3]
SCENE = "demo_physics"
SIZE = "96x54"
FRAMES = 12


def run(*args, env=None, expect=0):
    p = subprocess.run([RTRT, *args], capture_output=True, text=True, env=env, timeout=300)
    if p.returncode != expect:
        sys.exit(f"FAIL: rtrt {' '.join(args)}: exit {p.returncode}, expected {expect}\n"
                 f"stdout:\n{p.stdout}\nstderr:\n{p.stderr}")
    return p.stdout + p.stderr


def check(condition, what):
    if not condition:
        sys.exit("FAIL: " + what)
    print("ok:", what)


def frame(folder, i):
    return os.path.join(folder, "frames", f"frame_{i:06d}.{FORMAT}")


def play_children(pid):
    """The `rtrt play` processes whose parent is PID."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                stat = f.read()
            with open(f"/proc/{entry}/cmdline", "rb") as f:
                argv = f.read().split(b"\0")
        except OSError:
            continue
        ppid = int(stat[stat.rindex(")") + 2:].split()[1])
        if ppid == pid and len(argv) > 1 and argv[1] == b"play":
            found.append(int(entry))
    return found


def set_subreaper(on):
    libc = ctypes.CDLL(None, use_errno=True)
    PR_SET_CHILD_SUBREAPER = 36
    if libc.prctl(PR_SET_CHILD_SUBREAPER, ctypes.c_ulong(1 if on else 0), ctypes.c_ulong(0),
                  ctypes.c_ulong(0), ctypes.c_ulong(0)) != 0:
        sys.exit(f"FAIL: prctl(PR_SET_CHILD_SUBREAPER): errno {ctypes.get_errno()}")


def test_task_ends_with_farm():
    """A farm killed with SIGKILL takes its running task with it: no orphan renders on beside the
    rerun. This process becomes the orphans' reaper, so that it can wait for the task."""
    folder = os.path.join(WORK, "killed")
    log_path = os.path.join(WORK, "killed.log")
    set_subreaper(True)
    with open(log_path, "w") as log:
        farm = subprocess.Popen([RTRT, "farm", SCENE, "--frames", "0:20000", "--size", "640x360",
                                 "--spp", "16", "--format", FORMAT, "-o", folder, "--local"],
                                stdout=log, stderr=subprocess.STDOUT)
    deadline = time.time() + 120
    tasks = []
    while not tasks and farm.poll() is None and time.time() < deadline:
        time.sleep(0.05)
        tasks = play_children(farm.pid)
    if not tasks:
        farm.kill()
        farm.wait()
        sys.exit(f"FAIL: the farm started no task\n{open(log_path).read()}")
    task = tasks[0]
    time.sleep(1.0)  # the task is rendering
    farm.send_signal(signal.SIGKILL)
    farm.wait()
    status = None
    deadline = time.time() + 30
    while time.time() < deadline:
        waited, status = os.waitpid(task, os.WNOHANG)
        if waited == task:
            break
        status = None
        time.sleep(0.05)
    if status is None:
        os.kill(task, signal.SIGKILL)
        os.waitpid(task, 0)
    set_subreaper(False)
    check(status is not None and os.WIFEXITED(status) and os.WEXITSTATUS(status) == 143,
          f"a farm killed with SIGKILL takes its task with it (SIGTERM, exit 143; status {status})")
    check(not [f for f in os.listdir(os.path.join(folder, "frames"))
               if re.search(rf"\.partial{task}(\D|$)", f)],
          "the task removed its unfinished frame on the way out")
    shutil.rmtree(folder)


def fake_sbatch(folder, script):
    """A bin folder whose sbatch runs script (sh), for PATH."""
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "sbatch")
    with open(path, "w") as f:
        f.write("#!/bin/sh\n" + script + "\n")
    os.chmod(path, 0o755)
    return dict(os.environ, PATH=folder)


def test_refused_submission(farm):
    """sbatch refusing a job leaves the folder as the run found it; what it took stays recorded."""
    refusing = fake_sbatch(os.path.join(WORK, "refusing_bin"),
                           'echo "sbatch: error: invalid partition specified: gpux" >&2; exit 1')
    new = os.path.join(WORK, "refused", "job")
    out = run(*farm[:-1], new, env=refusing, expect=1)
    check("sbatch: error: invalid partition specified: gpux" in out and
          f"{new}: sbatch refused the render array (exit 1; its message is above); nothing was "
          "submitted or kept" in out and "--local" in out and
          not os.path.exists(os.path.join(WORK, "refused")),
          "a first submission sbatch refuses: exit 1, its message, and no folder left")
    empty = os.path.join(WORK, "refused_empty")
    os.makedirs(empty)
    run(*farm[:-1], empty, env=refusing, expect=1)
    check(os.listdir(empty) == [], "a user's empty folder is left empty when sbatch refuses")
    # The corrected command with other settings is then not refused for the first one's.
    other = [("32x18" if a == SIZE else a) for a in farm[:-1]]
    out = run(*other, empty, "--dry-run")
    check("dry run" in out, "a run of other settings into that folder is not refused")

    resumed = os.path.join(WORK, "refused_resume")
    shutil.copytree(os.path.join(WORK, "job"), resumed,
                    ignore=shutil.ignore_patterns("video.mp4", "contact_sheet.png"))
    before = open(os.path.join(resumed, "farm.json")).read()
    # Other Slurm options than the job's: refused, they are not left in its farm.json.
    run(*farm[:-1], resumed, "--partition", "gpux", env=refusing, expect=1)
    check(open(os.path.join(resumed, "farm.json")).read() == before and
          os.listdir(os.path.join(resumed, "slurm")) == [],
          "a job's folder keeps its farm.json and no unsubmitted script when sbatch refuses")

    # The render array taken, its assembly refused: the render job stays recorded.
    half = fake_sbatch(os.path.join(WORK, "half_bin"),
                       'case "$*" in *--dependency*) echo "sbatch: error: slurmctld down" >&2; '
                       'exit 1;; esac; echo "4242;cluster"')
    taken = os.path.join(WORK, "refused_assembly")
    out = run(*farm[:-1], taken, env=half, expect=1)
    check("slurmctld down" in out and "render job 4242 is queued and recorded" in out,
          "a refused assembly says the render job is queued and what to do once it has ended")
    recorded = json.load(open(os.path.join(taken, "farm.json")))["submissions"]
    check([s.get("render") for s in recorded] == ["4242"] and
          os.listdir(os.path.join(taken, "slurm")) == ["render-1.sbatch"],
          f"a refused assembly keeps the submitted render job recorded ({recorded})")


def fake_slurm(folder, sbatch, squeue):
    """fake_sbatch's bin folder with an squeue that runs squeue (sh) too."""
    env = fake_sbatch(folder, sbatch)
    with open(os.path.join(folder, "squeue"), "w") as f:
        f.write("#!/bin/sh\n" + squeue + "\n")
    os.chmod(os.path.join(folder, "squeue"), 0o755)
    return env


def test_unknown_queue(farm):
    """A queue squeue cannot report is no empty queue: no second submission, no false status;
    ids sbatch took are never lost without a word."""
    down = "echo 'slurm_load_jobs error: Unable to contact slurm controller' >&2; exit 1"
    unreachable = fake_slurm(os.path.join(WORK, "down_bin"), 'echo "501;cluster"', down)
    folder = os.path.join(WORK, "unknown_queue")
    run(*farm[:-1], folder, env=unreachable)
    out = run(*farm[:-1], folder, env=unreachable, expect=1)
    recorded = json.load(open(os.path.join(folder, "farm.json")))["submissions"]
    check("Unable to contact slurm controller" in out and
          "cannot tell whether its Slurm jobs (render 501 assemble 501) are still queued" in out and
          "--ignore-queue" in out and len(recorded) == 1,
          "a rerun while squeue fails is refused, not submitted a second time")
    out = run("farm", "--status", folder, env=unreachable, expect=3)
    check("Slurm: cannot tell whether render 501 assemble 501 still run" in out and
          "to finish it" not in out, "--status says it cannot tell, and suggests no rerun")
    missing = fake_sbatch(os.path.join(WORK, "no_squeue_bin"), 'echo "502;cluster"')
    out = run(*farm[:-1], folder, env=missing, expect=1)
    check("squeue is not on PATH here" in out, "a machine without squeue cannot tell either")
    run(*farm[:-1], folder, "--ignore-queue", env=missing)
    recorded = json.load(open(os.path.join(folder, "farm.json")))["submissions"]
    check([s["render"] for s in recorded] == ["501", "502"],
          "--ignore-queue submits once the user says the jobs have ended")
    # squeue asked about one id at a time fails for a forgotten one: it is always asked two.
    asked = os.path.join(WORK, "squeue_args")
    listing = fake_slurm(os.path.join(WORK, "listing_bin"), 'echo "503"',
                         f'echo "$*" > {asked}; exit 0')
    single = os.path.join(WORK, "single_id")
    shutil.copytree(os.path.join(WORK, "job"), single)
    os.remove(os.path.join(single, "video.mp4"))
    run(*farm[:-1], single, env=listing)  # every frame done: only the assembly, one id
    run("farm", "--status", single, env=listing, expect=3)
    check("-j 503,503 " in open(asked).read(), "a single job id is given to squeue twice")

    # sbatch exited 0 without an id: it may have taken the job, so its script stays.
    wordy = fake_sbatch(os.path.join(WORK, "wordy_bin"), 'echo "Submitted batch job 777"')
    folder = os.path.join(WORK, "no_id")
    out = run(*farm[:-1], folder, env=wordy, expect=1)
    check('sbatch exited 0 but printed no job id for the render array (it printed "Submitted '
          'batch job 777"); it' in out and "squeue --me" in out and
          os.path.exists(os.path.join(folder, "slurm", "render-1.sbatch")),
          "sbatch's exit 0 without an id is said with its output, and the script stays")
    other = [("32x18" if a == SIZE else a) for a in farm[:-1]]
    out = run(*other, folder, "--dry-run", expect=2)
    check("holds frames of other settings" in out,
          "a submission of unknown id pins the folder to its settings")
    # Interrupted while sbatch hangs: the folder holds a start without frames or jobs, which the
    # corrected command with other settings replaces.
    interrupting = fake_sbatch(os.path.join(WORK, "interrupting_bin"),
                               "kill -INT $PPID; sleep 1; exit 1")
    folder = os.path.join(WORK, "interrupted")
    run(*farm[:-1], folder, env=interrupting, expect=130)
    out = run("farm", "--status", folder, expect=3)
    check("Slurm: nothing submitted\n" in out, "--status of an interrupted start: nothing submitted")
    other = [("32x18" if a == SIZE else a) for a in farm[:-1]]
    check("dry run" in run(*other, folder, "--dry-run"),
          "a start interrupted before any frame or job does not hold the folder to its settings")
    # farm.json cannot take the id (a folder in its place stands in for a full disk).
    blocking = fake_sbatch(os.path.join(WORK, "blocking_bin"),
                           'job=${2%/slurm/*}; /bin/rm "$job/farm.json"; '
                           '/bin/mkdir "$job/farm.json"; echo 601')
    out = run(*farm[:-1], os.path.join(WORK, "unrecorded"), env=blocking, expect=1)
    check("Slurm took job 601 (render 601 assemble -)" in out and "scancel 601" in out,
          "a submitted id farm.json cannot record is named, with what to do")


def test_broken_video(farm):
    """A video ffmpeg exits 0 on but did not finish is no assembly: not kept, made again."""
    job = os.path.join(WORK, "job")
    broken = os.path.join(WORK, "broken_video")
    shutil.copytree(job, broken, ignore=shutil.ignore_patterns("video.mp4", "contact_sheet.png"))
    silent = fake_sbatch(os.path.join(WORK, "silent_ffmpeg_bin"), "exit 0")
    os.rename(os.path.join(WORK, "silent_ffmpeg_bin", "sbatch"),
              os.path.join(WORK, "silent_ffmpeg_bin", "ffmpeg"))
    silent["PATH"] += ":" + os.environ["PATH"]
    out = run("farm", "--assemble", broken, env=silent, expect=1)
    check("ffmpeg exited 0, but the file it wrote is empty" in out and
          not os.path.exists(os.path.join(broken, "video.mp4")) and
          not [f for f in os.listdir(broken) if "partial" in f],
          "an ffmpeg that exits 0 writing nothing: exit 1, no video, no temporary")
    # A video cut short before its index (as ffmpeg 5.1 leaves one on a full disk, exit 0) that
    # an earlier rtrt kept: the job is not done, and the rerun makes it again.
    with open(os.path.join(job, "video.mp4"), "rb") as f:
        whole = f.read()
    with open(os.path.join(broken, "video.mp4"), "wb") as f:
        f.write(whole[:len(whole) // 2])
    shutil.copy(os.path.join(job, "contact_sheet.png"), broken)
    status = run("farm", "--status", broken, expect=3)
    check("video: not made yet" in status, "--status does not count a cut-short video as made")
    # A FIFO under the video's name: --status answers at once, and a run is refused before it
    # renders anything (it had hung on the check, then failed only at the assembly).
    fifo = os.path.join(WORK, "fifo_video")
    shutil.copytree(job, fifo, ignore=shutil.ignore_patterns("video.mp4"))
    os.remove(os.path.join(fifo, "frames", "frame_000003." + FORMAT))
    os.mkfifo(os.path.join(fifo, "video.mp4"))
    status = run("farm", "--status", fifo, expect=3)
    check("video: not made yet" in status, "--status of a job whose video is a FIFO: exit 3")
    out = run(*farm[:-1], fifo, "--local", expect=2)
    check("video.mp4: is not a regular file" in out and "task" not in out,
          "a run whose video is a FIFO is refused (exit 2) before any task")
    out = run(*farm[:-1], broken, "--local")
    check("are ready" in out and "task" not in out and
          open(os.path.join(broken, "video.mp4"), "rb").read() == whole,
          "the rerun makes the video again from the frames it has")


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    ref = os.path.join(WORK, "ref")
    os.makedirs(ref)
    run("play", SCENE, "--headless", "--frames", str(FRAMES), "--size", SIZE, "--backend", "cpu",
        "-o", os.path.join(ref, f"frame_%06d.{FORMAT}"))
    job = os.path.join(WORK, "job")
    farm = ["farm", SCENE, "--frames", f"0:{FRAMES}", "--shards", "3", "--size", SIZE,
            "--format", FORMAT, "-o", job]

    # A dry run prints both scripts and writes nothing.
    out = run(*farm, "--dry-run")
    check("#SBATCH --array=0-2" in out and "0) ranges=\"0:4\"" in out and
          "2) ranges=\"8:12\"" in out and "--dependency=afterok:RENDER_JOB_ID" in out,
          "dry run prints the render array and the assembly after it")
    check(not os.path.exists(job), "dry run writes nothing")
    out = run(*farm, "--backend", "cuda", "--dry-run")
    check("--backend cuda without --gpu: the tasks ask Slurm for no GPU" in out,
          "CUDA tasks that ask Slurm for no GPU are warned of")

    # Without Slurm: said so, with the local command, and nothing written.
    no_slurm = dict(os.environ, PATH="/nonexistent")
    out = run(*farm, env=no_slurm, expect=1)
    check("Slurm is not installed here (no sbatch on PATH)" in out and "--local" in out,
          "without sbatch rtrt says so and shows the local command")
    check(not os.path.exists(job), "nothing written when Slurm is missing")

    # --local: the same frames as play --headless, the manifest, the video.
    out = run(*farm, "--local")
    for i in range(FRAMES):
        if not filecmp.cmp(frame(job, i), os.path.join(ref, f"frame_{i:06d}.{FORMAT}"),
                           shallow=False):
            sys.exit(f"FAIL: farm frame {i} differs from play --headless's")
    check(True, f"--local's {FRAMES} frames equal play --headless's byte for byte")
    probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0",
                            "-show_entries", "stream=codec_name,width,height,nb_read_frames",
                            "-of", "csv=p=0", os.path.join(job, "video.mp4")],
                           capture_output=True, text=True)
    check(probe.stdout.strip() == f"h264,96,54,{FRAMES}",
          f"video.mp4 is H.264 96x54 with {FRAMES} frames ({probe.stdout.strip()})")
    check(os.path.getsize(os.path.join(job, "contact_sheet.png")) > 0, "contact sheet written")
    status = run("farm", "--status", job)
    check(f"{FRAMES} of {FRAMES} frames done" in status, "status: every frame done, exit 0")
    check(not [f for f in os.listdir(job) if "partial" in f or f.endswith(".ffconcat")],
          "no temporary left in the job's folder")

    # Resume: a deleted frame, a corrupted one and the video gone; only those two are rendered.
    os.remove(frame(job, 5))
    with open(frame(job, 9), "r+b") as f:
        f.seek(20)
        f.write(b"\xff\x00\xff")
    os.remove(os.path.join(job, "video.mp4"))
    status = run("farm", "--status", job, expect=3)
    check("1 missing (5)" in status and "1 corrupt (9" in status and "not made yet" in status,
          "status names the missing and the corrupt frame, exit 3")
    out = run(*farm, "--local")
    tasks = re.findall(r"task \d+ of \d+: frames (\d+:\d+)", out)
    check(tasks == ["5:6", "9:10"], f"the resume renders only frames 5 and 9 ({tasks})")
    check(filecmp.cmp(frame(job, 5), os.path.join(ref, f"frame_{5:06d}.{FORMAT}"), shallow=False)
          and filecmp.cmp(frame(job, 9), os.path.join(ref, f"frame_{9:06d}.{FORMAT}"),
                          shallow=False), "the rerendered frames equal the reference")
    out = run(*farm, "--local")
    check("nothing to do" in out, "a third run has nothing to do")

    # Tasks run elsewhere (a Kubernetes Indexed Job): play --manifest into a new folder, then the
    # farm command takes their frames up and only assembles.
    k8s = os.path.join(WORK, "k8s")
    os.makedirs(os.path.join(k8s, "frames"))
    os.makedirs(os.path.join(k8s, "manifest"))
    for index, (a, b) in enumerate([(0, 7), (7, FRAMES)]):
        run("play", SCENE, "--headless", "--frames", f"{a}:{b}", "--size", SIZE, "--backend", "cpu",
            "-o", os.path.join(k8s, "frames", f"frame_%06d.{FORMAT}"), "--manifest",
            os.path.join(k8s, "manifest", f"k8s-{index}.tsv"))
    k8s_farm = list(farm)
    k8s_farm[k8s_farm.index(job)] = k8s
    out = run(*k8s_farm, "--local")
    check(f"{FRAMES} of {FRAMES} frames done" in out and "task" not in out and
          os.path.exists(os.path.join(k8s, "video.mp4")),
          "frames rendered elsewhere with --manifest are taken up: the farm only assembles")

    # Frames rendered elsewhere at another size: no farm.json says how they were made, and a frame
    # of another size was made with other settings, so the run is refused (exit 2) and the folder
    # left as it was (they had been taken up, and scaled into the video).
    adopt = os.path.join(WORK, "adopt")
    os.makedirs(os.path.join(adopt, "frames"))
    os.makedirs(os.path.join(adopt, "manifest"))
    run("play", SCENE, "--headless", "--frames", "0:4", "--size", "32x18", "--backend", "cpu",
        "-o", os.path.join(adopt, "frames", f"frame_%06d.{FORMAT}"), "--manifest",
        os.path.join(adopt, "manifest", "k8s-0.tsv"))
    out = run("farm", SCENE, "--frames", "0:4", "--size", SIZE, "--format", FORMAT, "-o", adopt,
              "--local", expect=2)
    check(f"frame_000000.{FORMAT}: is 32x18, but the job renders {SIZE}" in out and
          sorted(os.listdir(adopt)) == ["frames", "manifest"] and
          len(os.listdir(os.path.join(adopt, "frames"))) == 4,
          "frames of another size made elsewhere are refused (exit 2) and left alone")

    # A refused run leaves a user's folder as it found it: no lock file, nothing else.
    user = os.path.join(WORK, "userdir")
    os.makedirs(user)
    with open(os.path.join(user, "notes.txt"), "w") as f:
        f.write("x\n")
    out = run("farm", SCENE, "--frames", "0:2", "--size", "8x8", "--format", FORMAT, "-o", user,
              "--local", expect=2)
    check("holds notes.txt but no farm job" in out and os.listdir(user) == ["notes.txt"],
          "a folder of other files is refused and keeps only what it held")

    # Options of two modes together are refused, naming both, instead of one being ignored.
    out = run("farm", "--status", job, "--assemble", job, expect=2)
    check("--status excludes --assemble" in out, "--status with --assemble: exit 2, both named")
    out = run("farm", "--status", job, "--local", "--frames", "0:3", "--shards", "7", expect=2)
    check("excludes" in out and "--status" in out and
          ("--local" in out or "--frames" in out or "--shards" in out),
          "--status with a job's options: exit 2, both named")
    dry_local = os.path.join(WORK, "dry_local")
    out = run("farm", SCENE, "--frames", "0:6", "-o", dry_local, "--dry-run", "--local", expect=2)
    check("--dry-run excludes --local" in out and not os.path.exists(dry_local),
          "--dry-run with --local: exit 2, nothing written")

    # Another size into the same folder is refused, naming the difference.
    other = list(farm)
    other[other.index(SIZE)] = "64x36"
    out = run(*other, "--local", expect=2)
    check("holds frames of other settings (size 96x54 there, 64x36 here)" in out,
          "a folder of other settings is refused with exit 2")
    out = run("farm", "--status", os.path.join(WORK, "nowhere"), expect=2)
    check("a folder made by `rtrt farm`" in out, "status of a folder that is no job: exit 2")
    out = run("play", SCENE, "--headless", "--frames", "2", "--size", SIZE, "-o",
              os.path.join(WORK, f"m_%d.{FORMAT}"), "--manifest",
              os.path.join(WORK, "nowhere", "m.tsv"), expect=2)
    check("--manifest" in out and not os.path.exists(os.path.join(WORK, f"m_0.{FORMAT}")),
          "an unwritable --manifest fails before any frame")

    # One rtrt farm at a time in a folder: while another process holds the folder's lock, a run
    # is refused with exit 2 and names the holder; the lock goes with its holder.
    with open(os.path.join(job, ".rtrt-farm.lock"), "r+") as held:
        fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
        held.truncate(0)
        held.write("process 4242 on elsewhere\n")
        held.flush()
        out = run(*farm, "--local", expect=1)
        check("another rtrt farm (process 4242 on elsewhere) is working in this folder" in out,
              "a second run in a folder that is being worked in is refused, naming the holder "
              "(exit 1: busy, not bad input)")
        assembly = subprocess.Popen([RTRT, "farm", "--assemble", job], stdout=subprocess.PIPE,
                                    stderr=subprocess.STDOUT, text=True)
        time.sleep(1.0)
        check(assembly.poll() is None, "--assemble waits for the lock instead of failing")
    out, _ = assembly.communicate(timeout=120)
    check(assembly.returncode == 0 and "wrote" in out,
          "--assemble goes on once the holder lets go")
    check("waiting up to 300 s for another rtrt farm (process 4242 on elsewhere)" in out,
          "--assemble says what it waits for")
    out = run(*farm, "--local")
    check("nothing to do" in out, "once the holder is gone the folder is free")
    with open(os.path.join(job, ".rtrt-farm.lock"), "r+") as held:
        fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
        held.truncate(0)
        held.write("process 4242 on \x1b]0;owned\x07\x1b[2Jhost\n")
        held.flush()
        out = run(*farm, "--local", expect=1)
    check("(process 4242 on \\x1b]0;owned\\x07\\x1b[2Jhost)" in out and "\x1b" not in out,
          "the holder's text is printed with its control characters escaped")
    fresh = os.path.join(WORK, "fresh")
    out = run(*farm[:-1], os.path.join(fresh, "a", "job"), env=no_slurm, expect=1)
    check(not os.path.exists(fresh),
          "the new folders made for the lock go when nothing is written")

    # Temporaries left by a process of this host that is gone (killed with SIGKILL) are removed
    # by the next run; one whose process still runs, or another host's, is left alone.
    host = re.sub(r"[^A-Za-z0-9-]", "-", socket.gethostname())
    gone = subprocess.Popen(["true"])
    gone.wait()
    stale = os.path.join(job, "frames", f".frame_000003.partial{gone.pid}-{host}.{FORMAT}")
    live = os.path.join(job, "frames", f".frame_000004.partial{os.getpid()}-{host}.{FORMAT}")
    elsewhere = os.path.join(job, f".video.partial{gone.pid}-{host}x.mp4")
    for path in (stale, live, elsewhere):
        open(path, "w").close()
    out = run(*farm, "--local")
    check("removed 1 unfinished file left by processes that are gone" in out and
          not os.path.exists(stale) and os.path.exists(live) and os.path.exists(elsewhere),
          "a dead process's temporary is removed; a live one's and another host's are kept")
    os.remove(live)
    os.remove(elsewhere)

    # A farm task plays the scene its job was made from: an edited scene fails the task (exit 2)
    # instead of mixing its frames into the job.
    digest = json.load(open(os.path.join(job, "farm.json")))["scene_checksum"]
    scene = os.path.join(WORK, "scene.json")
    with open(os.path.join(WORK, "tri.obj"), "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    with open(scene, "w") as f:
        f.write('{ "models": { "m": { "type": "mesh", "file": "tri.obj" } },'
                ' "instances": [ { "model": "m" } ] }\n')
    out = run("play", scene, "--headless", "--frames", "1", "--size", SIZE, "-o",
              os.path.join(WORK, f"c_%d.{FORMAT}"), "--scene-checksum", "0123456789abcdef",
              expect=2)
    check("changed since its farm job was made" in out and
          not os.path.exists(os.path.join(WORK, f"c_0.{FORMAT}")),
          "play --scene-checksum refuses a scene of another checksum before any frame")
    check(re.fullmatch(r"[0-9a-f]{16}", digest) is not None,
          f"farm.json keeps the scene's checksum ({digest})")
    # The checksum covers the files the scene brings in: a model edited after the job was made
    # fails its task too (its frames had been mixed into the job).
    modelled = os.path.join(WORK, "modelled")
    run("farm", scene, "--frames", "0:2", "--size", SIZE, "--format", FORMAT, "--dry-run", "-o",
        modelled)
    run("farm", scene, "--frames", "0:2", "--size", SIZE, "--format", FORMAT, "--local", "-o",
        modelled)
    with open(os.path.join(WORK, "tri.obj"), "a") as f:
        f.write("v 0 0 1\n")
    os.remove(frame(modelled, 1))
    out = run("farm", scene, "--frames", "0:2", "--size", SIZE, "--format", FORMAT, "--local",
              "-o", modelled, expect=2)
    check("scene checksum" in out, "a resume after the scene's model was edited is refused")
    out = run("farm", "--status", modelled, expect=3)
    check("the tasks refuse the scene now" in out and "changed since its farm job was made" in out
          and "to finish it" not in out,
          "--status of a job whose scene was edited says so instead of a rerun that is refused")
    with open(os.path.join(modelled, ".rtrt-farm.lock"), "r+") as held:
        fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
        held.truncate(0)
        held.write("process 4242 on elsewhere\n")
        held.flush()
        out = run("farm", "--status", modelled, expect=3)
    check("another rtrt farm (process 4242 on elsewhere) is working in this folder" in out and
          "to finish it" not in out, "--status names a run that works in the folder")
    # Every frame done and only the video missing: --status points at --assemble, which needs no
    # scene, even one edited since (it had pointed at the refused rerun).
    whole = os.path.join(WORK, "whole")
    run("farm", scene, "--frames", "0:2", "--size", SIZE, "--format", FORMAT, "--local", "-o",
        whole)
    os.remove(os.path.join(whole, "video.mp4"))
    with open(os.path.join(WORK, "tri.obj"), "a") as f:
        f.write("v 0 0 2\n")
    out = run("farm", "--status", whole, expect=3)
    check(f"to finish it: rtrt farm --assemble {whole}" in out and "refuse the scene" not in out,
          "--status of a job whose frames are all done points at --assemble")
    run("farm", "--assemble", whole)
    check(os.path.exists(os.path.join(whole, "video.mp4")), "--assemble then makes the video")
    # A '?' in the job's folder: ffmpeg took the contact sheet's relative entries as URLs whose
    # query began there, and looked for the frames elsewhere (here: nowhere, so the run failed).
    queried = os.path.join(WORK, "par?ent", "job")
    run("farm", scene, "--frames", "0:2", "--size", SIZE, "--format", FORMAT, "--local", "-o",
        queried)
    check(os.path.exists(os.path.join(queried, "contact_sheet.png")),
          "a job folder with '?' in its path gets its contact sheet")
    # Moved into a folder with a quote (which --output refuses, but a move can make), the job
    # still assembles: the list's entries escape it.
    quoted = os.path.join(WORK, "it's")
    shutil.copytree(whole, quoted)
    for made in ("video.mp4", "contact_sheet.png"):
        os.remove(os.path.join(quoted, made))
    run("farm", "--assemble", quoted)
    check(os.path.exists(os.path.join(quoted, "contact_sheet.png")),
          "a job moved under a folder with a quote assembles")
    # A frame of another size (a retried task elsewhere with other settings) is refused, not
    # scaled into the video.
    os.remove(frame(quoted, 1))
    run("play", scene, "--headless", "--frames", "1:2", "--size", "48x24", "-o",
        os.path.join(quoted, "frames", f"frame_%06d.{FORMAT}"), "--manifest",
        os.path.join(quoted, "manifest", "elsewhere.tsv"))
    os.remove(os.path.join(quoted, "video.mp4"))
    out = run("farm", "--assemble", quoted, expect=2)
    check("frame_000001" in out and "rendered with other settings" in out and
          not os.path.exists(os.path.join(quoted, "video.mp4")),
          "--assemble refuses a frame of another size")
    # With --local this machine assembles: without ffmpeg nothing is rendered first.
    no_ffmpeg = os.path.join(WORK, "no_ffmpeg")
    out = run("farm", scene, "--frames", "0:2", "--size", SIZE, "--format", FORMAT, "--local",
              "-o", no_ffmpeg, env=dict(os.environ, PATH=os.path.join(WORK, "empty_bin")),
              expect=1)
    check("ffmpeg is not installed" in out and not os.path.exists(no_ffmpeg),
          "--local without ffmpeg is refused before any frame, leaving no folder")
    job_digest = json.load(open(os.path.join(modelled, "farm.json")))["scene_checksum"]
    # The same files under other paths (a node's own copy of the models) have the same
    # checksum, whichever way the paths sort.
    for models in ("a_models", "zz_models"):
        os.makedirs(os.path.join(WORK, models))
        shutil.copy(os.path.join(WORK, "tri.obj"), os.path.join(WORK, models))
    os.makedirs(os.path.join(WORK, "s"))
    with open(os.path.join(WORK, "s", "scene.json"), "w") as f:
        f.write('{ "models": { "m": { "type": "mesh", "file": "@models/tri.obj" } },'
                ' "instances": [ { "model": "m" } ] }\n')

    def dry_checksum(models):
        out = run("farm", os.path.join(WORK, "s", "scene.json"), "--frames", "0:2", "--size",
                  SIZE, "--format", FORMAT, "--dry-run", "-o", os.path.join(WORK, "dry_job"),
                  env=dict(os.environ, RTRT_MODEL_DIR=os.path.join(WORK, models)))
        return re.search(r"--scene-checksum ([0-9a-f]{16})", out).group(1)
    here, there = dry_checksum("a_models"), dry_checksum("zz_models")
    check(here == there, f"the same model in another folder gives the same checksum ({there})")
    out = run("play", scene, "--headless", "--frames", "1", "--size", SIZE, "-o",
              os.path.join(WORK, f"m_%d.{FORMAT}"), "--scene-checksum", job_digest, expect=2)
    check("changed since its farm job was made, or a file it brings in did" in out,
          "a task whose scene's model was edited fails as bad input")

    # A hostile farm.json: a FIFO is refused at once instead of waited on; Slurm fields that are
    # not names are refused instead of printed into a command line.
    fifo_job = os.path.join(WORK, "fifo")
    os.makedirs(fifo_job)
    os.mkfifo(os.path.join(fifo_job, "farm.json"))
    p = subprocess.run([RTRT, "farm", "--status", fifo_job], capture_output=True, text=True,
                       timeout=60)
    check(p.returncode == 2 and "not a regular file" in p.stderr,
          "a farm.json that is a FIFO: exit 2 at once")
    p = subprocess.run([RTRT, *farm[:-1], fifo_job, "--local"], capture_output=True, text=True,
                       timeout=60)
    check(p.returncode == 2 and "farm.json: not a regular file" in p.stderr and
          os.listdir(fifo_job) == ["farm.json"],
          "a run into a folder whose farm.json is a FIFO: exit 2, it is not a regular file")
    dir_job = os.path.join(WORK, "json_dir")
    os.makedirs(os.path.join(dir_job, "farm.json"))
    out = run(*farm[:-1], dir_job, "--local", expect=2)
    check("farm.json: not a regular file" in out and os.listdir(dir_job) == ["farm.json"],
          "a run into a folder whose farm.json is a folder: exit 2, it is not a regular file")
    lock_dir = os.path.join(WORK, "lock_dir")
    os.makedirs(os.path.join(lock_dir, ".rtrt-farm.lock"))
    out = run(*farm[:-1], lock_dir, "--local", expect=2)
    check(".rtrt-farm.lock: is a folder where rtrt farm keeps its lock file; remove it" in out,
          "a lock file that is a folder: exit 2, saying to remove it")
    newer = os.path.join(WORK, "newer")
    os.makedirs(newer)
    with open(os.path.join(job, "farm.json")) as f:
        description = json.load(f)
    description["version"] = 2
    with open(os.path.join(newer, "farm.json"), "w") as f:
        json.dump(description, f)
    out = run("farm", "--status", newer, expect=2)
    check("version: the job was written by a newer rtrt (version 2; this rtrt reads version 1)"
          in out, "a farm.json of a later version names the newer rtrt")
    # A file where the job keeps its manifests read as no frames done (--status said 0 of N).
    filed = os.path.join(WORK, "filed")
    os.makedirs(filed)
    shutil.copy(os.path.join(job, "farm.json"), filed)
    with open(os.path.join(filed, "manifest"), "w") as f:
        f.write("not a folder\n")
    out = run("farm", "--status", filed, expect=2)
    check("manifest: is not a folder, where the job keeps its manifest" in out,
          "--status of a job whose manifest folder is a file: exit 2, saying what to move")
    # Folders on shared storage, linked: a link to a folder is one, a dangling link is named so.
    os.remove(os.path.join(filed, "manifest"))
    os.symlink(os.path.join(job, "manifest"), os.path.join(filed, "manifest"))
    os.symlink(os.path.join(WORK, "unmounted"), os.path.join(filed, "frames"))
    out = run("farm", "--status", filed, expect=2)
    check("frames: is a link to " in out and "which is not there (is its storage mounted here?)"
          in out, "--status with a dangling frames link: exit 2, naming the link's target")
    os.remove(os.path.join(filed, "frames"))
    os.symlink(os.path.join(job, "frames"), os.path.join(filed, "frames"))
    linked, own = [subprocess.run([RTRT, "farm", "--status", folder], capture_output=True,
                                  text=True) for folder in (filed, job)]
    done = [re.search(r"\d+ of \d+ frames done", r.stdout) for r in (linked, own)]
    # (Its exit status is 3 where the job's is 0: the video is the job folder's, not linked.)
    check(done[0] and done[1] and done[0].group(0) == done[1].group(0),
          "--status with frames and manifest linked to a job's folders reads them as that job's")
    bad = os.path.join(WORK, "bad_partition")
    shutil.copytree(job, bad, ignore=shutil.ignore_patterns("frames", "video.mp4"))
    with open(os.path.join(bad, "farm.json")) as f:
        description = json.load(f)
    description["partition"] = "gpu; touch pwned #"
    with open(os.path.join(bad, "farm.json"), "w") as f:
        json.dump(description, f)
    out = run("farm", "--status", bad, expect=2)
    check("partition: expected a Slurm name" in out, "a partition that is no Slurm name: exit 2")

    test_refused_submission(farm)
    test_unknown_queue(farm)
    test_broken_video(farm)

    # A folder that cannot be made (a file in the way) is bad input, exit 2.
    blocker = os.path.join(WORK, "a_file")
    open(blocker, "w").close()
    out = run(*farm[:-1], os.path.join(blocker, "sub"), "--local", expect=2)
    check("a_file/sub" in out, "an output folder under a file: exit 2")

    test_task_ends_with_farm()
    print("farm_cli: all checks passed")


if __name__ == "__main__":
    main()
