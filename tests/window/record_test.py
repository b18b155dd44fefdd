#!/usr/bin/env python3
"""`rtrt play --record out.mp4` in a real window (under Xvfb): the video has every frame shown,
at the window's size, and each decoded frame matches the frame that `--record DIR` writes for the
same fixed-step run (H.264 at CRF 18 is lossy: mean absolute error under 2 of 255 per channel);
a recording's frames are play --headless's frames; F12 takes the first free
rtrt-screenshot-N.png, leaving an earlier run's.

usage: record_test.py LAUNCHER... -- RTRT WORK_DIR SCENE BACKEND
"""
import os
import shutil
import subprocess
import sys

split = sys.argv.index("--")
LAUNCHER = sys.argv[1:split]
RTRT, WORK, SCENE, BACKEND = sys.argv[split + 1:split + 5]
FRAMES, W, H = 24, 160, 90


def fail(what):
    sys.exit("FAIL: " + what)


def play(record):
    p = subprocess.run([*LAUNCHER, RTRT, "play", SCENE, "--backend", BACKEND, "--size", f"{W}x{H}",
                        "--frames", str(FRAMES), "--no-vsync", "--record", record],
                       capture_output=True, text=True, timeout=300)
    if p.returncode != 0:
        fail(f"play --record {record}: exit {p.returncode}\n{p.stdout}\n{p.stderr}")
    return p.stdout


def raw_frames(args):
    """rgb24 bytes of every frame ffmpeg decodes from ARGS' input."""
    p = subprocess.run(["ffmpeg", "-nostdin", "-v", "error", *args, "-f", "rawvideo",
                        "-pix_fmt", "rgb24", "-"], capture_output=True, timeout=120)
    if p.returncode != 0:
        fail("ffmpeg could not decode: " + p.stderr.decode())
    return p.stdout


def check_fullscreen_keeps_size():
    """A recording to PNG frames keeps the first frame's size, as the video does, when F11 makes
    the window fullscreen and back (frames 2 to 4 had been the screen's size)."""
    script = os.path.join(WORK, "fullscreen.script")
    with open(script, "w") as f:
        f.write("2 key F11\n5 key F11\n8 quit\n")
    folder = os.path.join(WORK, "fullscreen")
    p = subprocess.run([*LAUNCHER, RTRT, "play", SCENE, "--backend", BACKEND, "--size",
                        f"{W}x{H}", "--no-vsync", "--script", script, "--record", folder],
                       capture_output=True, text=True, timeout=300)
    if p.returncode != 0:
        fail(f"fullscreen recording: exit {p.returncode}\n{p.stderr}")
    sizes = set()
    for name in sorted(os.listdir(folder)):
        with open(os.path.join(folder, name), "rb") as f:
            header = f.read(24)
        sizes.add((int.from_bytes(header[16:20], "big"), int.from_bytes(header[20:24], "big")))
    if sizes != {(W, H)}:
        fail(f"fullscreen recording: frame sizes {sorted(sizes)}, expected only {W}x{H}")
    print(f"ok: F11 in a recording: every frame {W}x{H}")


def check_frames_match_headless():
    """A recording's frame k is play --headless's frame k: the scene after k fixed steps, the
    first one as loaded (the window had stepped before its first frame, so every recorded frame
    was the headless one after it). The camera moves, so an offset shows."""
    scene = os.path.join(WORK, "moving.json")
    with open(scene, "w") as f:
        f.write('{ "models": { "ball": { "type": "sphere" }, "floor": { "type": "plane" } },'
                ' "instances": [ { "model": "ball", "position": [0, 1, 0] },'
                ' { "model": "floor" } ],'
                ' "camera_path": [ { "time": 0, "position": [-3, 2, 5], "look_at": [0, 1, 0] },'
                ' { "time": 1, "position": [3, 2, 5], "look_at": [0, 1, 0] } ] }')
    recorded, headless = os.path.join(WORK, "moving_window"), os.path.join(WORK, "moving_headless")
    os.makedirs(headless)
    p = subprocess.run([*LAUNCHER, RTRT, "play", scene, "--backend", BACKEND, "--size",
                        f"{W}x{H}", "--frames", str(FRAMES), "--no-vsync", "--record", recorded],
                       capture_output=True, text=True, timeout=300)
    q = subprocess.run([RTRT, "play", scene, "--headless", "--backend", BACKEND, "--size",
                        f"{W}x{H}", "--frames", str(FRAMES), "-o",
                        os.path.join(headless, "f_%05d.png")], capture_output=True, text=True,
                       timeout=300)
    if p.returncode != 0 or q.returncode != 0:
        fail(f"moving scene: exits {p.returncode} (window), {q.returncode} (headless)\n"
             f"{p.stderr}\n{q.stderr}")
    window = raw_frames(["-i", os.path.join(recorded, "frame_%05d.png")])
    frames = raw_frames(["-i", os.path.join(headless, "f_%05d.png")])
    size = W * H * 3
    if len(window) != len(frames) or len(frames) != FRAMES * size:
        fail(f"moving scene: {len(window)} bytes recorded, {len(frames)} headless")
    # The window's 8-bit conversion rounds some values the other way: 1 of 255 apart at most
    # (a frame's neighbours differ by about 100 where the ball moves).
    differ = [i for i in range(FRAMES)
              if max(abs(a - b) for a, b in zip(window[i * size:(i + 1) * size],
                                                frames[i * size:(i + 1) * size])) > 1]
    if differ:
        fail(f"moving scene: recorded frames {differ} differ from play --headless's by more than "
             "1/255")
    print(f"ok: the {FRAMES} recorded frames of a moving camera are play --headless's frames "
          "(within 1/255)")


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    video = os.path.join(WORK, "session.mp4")
    out = play(video)
    if f"recorded {FRAMES} frames to {video}" not in out:
        fail("no 'recorded' line: " + out)
    probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0",
                            "-show_entries", "stream=codec_name,width,height,nb_read_frames",
                            "-of", "csv=p=0", video], capture_output=True, text=True).stdout
    if probe.strip() != f"h264,{W},{H},{FRAMES}":
        fail(f"expected h264,{W},{H},{FRAMES}, ffprobe says {probe.strip()}")
    print(f"ok: {video}: H.264, {W}x{H}, {FRAMES} frames")
    if [f for f in os.listdir(WORK) if "partial" in f]:
        fail("a temporary was left: " + str(os.listdir(WORK)))

    frames_dir = os.path.join(WORK, "frames")
    play(frames_dir)
    pngs = raw_frames(["-i", os.path.join(frames_dir, "frame_%05d.png")])
    decoded = raw_frames(["-i", video])
    if len(pngs) != len(decoded) or len(pngs) != FRAMES * W * H * 3:
        fail(f"sizes differ: {len(pngs)} bytes of frames, {len(decoded)} decoded")
    size = W * H * 3
    worst = 0.0
    for i in range(FRAMES):
        a, b = pngs[i * size:(i + 1) * size], decoded[i * size:(i + 1) * size]
        worst = max(worst, sum(abs(x - y) for x, y in zip(a, b)) / size)
    if worst >= 2.0:
        fail(f"a decoded frame differs from its PNG by {worst:.2f}/255 on average")
    print(f"ok: every decoded frame matches its PNG (worst mean error {worst:.2f}/255)")

    check_frames_match_headless()
    check_fullscreen_keeps_size()

    # F12 takes the first free rtrt-screenshot-N.png: an earlier run's file stays.
    shots = os.path.join(WORK, "shots")
    os.makedirs(shots)
    earlier = os.path.join(shots, "rtrt-screenshot-0.png")
    with open(earlier, "wb") as f:
        f.write(b"an earlier run's screenshot")
    script = os.path.join(WORK, "f12.script")
    with open(script, "w") as f:
        f.write("2 key F12\n4 quit\n")
    p = subprocess.run([*LAUNCHER, RTRT, "play", SCENE, "--backend", BACKEND, "--size", f"{W}x{H}",
                        "--no-vsync", "--script", script], cwd=shots, capture_output=True,
                       text=True, timeout=300)
    if p.returncode != 0 or "wrote rtrt-screenshot-1.png" not in p.stdout:
        fail(f"F12: exit {p.returncode}\n{p.stdout}\n{p.stderr}")
    if open(earlier, "rb").read() != b"an earlier run's screenshot":
        fail("F12 wrote over an earlier run's screenshot")
    with open(os.path.join(shots, "rtrt-screenshot-1.png"), "rb") as f:
        if f.read(8) != b"\x89PNG\r\n\x1a\n":
            fail("rtrt-screenshot-1.png is no PNG")
    print("ok: F12 wrote rtrt-screenshot-1.png beside an earlier run's rtrt-screenshot-0.png")


if __name__ == "__main__":
    main()
