#!/usr/bin/env python3
"""Option values and odd arguments found by probing the command line: each case's exit status,
message, and what must (not) be left behind.

- Integers and numbers are read in decimal: CLI11 read integers in C's base 0 ("017" was 15,
  "0x10" 16, a negative wrapped around in an unsigned option) and numbers as strtod does
  (hexadecimal floats). --size takes digits only; no option takes an empty value.
- bench convert's scratch folder has a name no one can foresee: a folder of its old name
  (rtrt_bench_convert_PID in the temporary folder) is neither used nor removed.
- bench soak refuses a run that takes fewer than two memory samples; fetch-models refuses a --dir
  that is a file; info reads a scene file of any name; benches take scene names; --traversal
  is refused on the CPU back end; play refuses a manifest or scene named like one of its frames.
- An output naming a file the scene reads (a glTF file's texture) is refused; .jp2 (written
  without its pixels) is refused, WebP beyond 16383 pixels before the render; a 1-pixel-wide
  heatmap renders (it had crashed).
- --frames says why a range is refused (reversed, beyond 10,000,000, empty, malformed).

usage: option_values_test.py RTRT WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys

RTRT, WORK = sys.argv[1], sys.argv[2]
shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
failures = []


def run(*args, env=None):
    return subprocess.run([RTRT, *args], capture_output=True, text=True, cwd=WORK, timeout=300,
                          env=dict(os.environ, **(env or {})))


def expect(name, args, status, text, env=None):
    r = run(*args, env=env)
    if r.returncode != status or text not in r.stderr + r.stdout:
        failures.append(f"{name}: exit {r.returncode} (expected {status}), wanted {text!r}:\n"
                        f"{r.stderr}{r.stdout[-400:]}")
    return r


image = ["render", "default", "--backend", "cpu", "--size", "8x4", "-o", "out.ppm"]
expect("octal depth", image + ["--max-depth", "017"], 2, "Value 17 not in range 1 to 16")
expect("hex depth", image + ["--max-depth", "0x3"], 2,
       '--max-depth: expected a whole number in decimal digits, got "0x3"')
expect("wrapped spp", image + ["--spp", "-18446744073709551612"], 2,
       '--spp: expected a whole number >= 0 in decimal digits')
expect("leading zero spp", image + ["--spp", "016"], 0, "wrote out.ppm")
# Past 32 bits the conversion had failed with the value alone as its message.
expect("spp beyond 32 bits", image + ["--spp", "4294967296"], 2,
       '--spp: "4294967296" is beyond the largest whole number this option takes (4294967295)')
expect("hex fps", ["play", "default", "--headless", "--frames", "1", "--fps", "0x10", "--backend",
                   "cpu", "--size", "8x4", "-o", "f%d.ppm"], 2,
       '--fps: expected a number in decimal notation, got "0x10"')
expect("nan exposure", image + ["--exposure", "nan"], 2, "--exposure: nan is not a finite number")
expect("fraction count", ["bench", "ecs", "--count", "5.5"], 2,
       '--count: expected a whole number >= 0 in decimal digits, got "5.5"')
unsized = ["render", "default", "--backend", "cpu", "-o", "sized.ppm"]
for size in ["-1x4", "+8x4", " 8x4", "8x4 "]:
    expect(f"size {size!r}", unsized + [f"--size={size}"], 2,
           f'--size: expected WIDTHxHEIGHT such as 1920x1080, got "{size}"')
expect("empty size", unsized + ["--size", ""], 2,
       "--size: an empty value: give one, or leave the option out")
if os.path.exists(os.path.join(WORK, "sized.ppm")):
    failures.append("a refused command wrote its output")
expect("decimal size", unsized + ["--size", "010x004"], 0, "(10x4,")

# The old scratch name, made before rtrt starts (exec keeps the shell's process id).
tmp = os.path.join(WORK, "tmp")
os.makedirs(tmp)
script = ('mkdir "$TMPDIR/rtrt_bench_convert_$$" && echo keep > "$TMPDIR/rtrt_bench_convert_$$/own" '
          '&& exec "$0" bench convert --models dragon_res4 --runs 1')
r = subprocess.run(["/bin/bash", "-c", script, RTRT], capture_output=True, text=True, cwd=WORK,
                   env=dict(os.environ, TMPDIR=tmp), timeout=300)
left = sorted(os.listdir(tmp))
models_fetched = "none of the models asked for is there" not in r.stderr
if not models_fetched:
    print("bench convert's scratch folder: skipped (dragon_res4 not fetched)")
elif r.returncode != 0 or len(left) != 1 or not os.path.exists(os.path.join(tmp, left[0], "own")):
    failures.append(f"bench convert: exit {r.returncode}, the temporary folder holds {left}:\n"
                    f"{r.stderr}")
if models_fetched:
    expect("no temporary folder", ["bench", "convert", "--models", "dragon_res4", "--runs", "1"],
           1, "TMPDIR: no folder for temporary files",
           env={"TMPDIR": os.path.join(WORK, "nowhere")})

expect("soak without samples", ["bench", "soak", "--backend", "cpu", "--frames", "5", "--every",
                                "1", "--warmup", "10"], 2,
       "--frames: 5 frames take 0 memory sample(s)")
with open(os.path.join(WORK, "afile"), "w") as f:
    f.write("x\n")
expect("fetch into a file", ["fetch-models", "--dir", "afile"], 2,
       "--dir: afile: is not a folder")
expect("fetch into nothing", ["fetch-models", "--dir", ""], 2, "--dir: an empty value")
shutil.copy(os.path.join(os.path.dirname(__file__), "..", "..", "assets", "scenes",
                         "teapot_shadow.json"), os.path.join(WORK, "T.Json"))
expect("info of a scene named .Json", ["info", "T.Json"], 0, "T.Json: scene file")
expect("info of an unknown kind", ["info", "afile"], 2, "afile: unknown kind of file")
expect("bench frame by name", ["bench", "frame", "teapot_shadow", "--backend", "cpu", "--frames",
                               "1", "--warmup", "0", "--size", "8x4"], 0, "teapot_shadow")
expect("traversal on the CPU", image + ["--traversal", "single"], 2,
       "--traversal: single: nested and single are the CUDA back end's traversals")
expect("one GPU written 01", image + ["--gpus", "01"], 0, "wrote out.ppm")
# A model or builder named twice is measured once: the report keeps one entry per name.
r = expect("repeated models", ["bench", "cpu", "--models", "cube,cube", "--builders",
                               "binned,binned", "--frames", "1"], 0, "cube")
if r.stdout.count("\ncube ") != 1:
    failures.append(f"bench cpu --models cube,cube: rows\n{r.stdout}")
# A report named like a benchmark's model file is refused before the benchmark (after it, the
# whole run was lost).
os.makedirs(os.path.join(WORK, "bench_models"))
with open(os.path.join(WORK, "bench_models", "dragon_vrip_res4.ply.gz"), "wb") as f:
    f.write(b"model")
for bench in ("cpu", "convert"):
    expect(f"bench {bench} report over its model",
           ["bench", bench, "--models", "dragon_res4", "-o", "bench_models/dragon_vrip_res4.ply.gz"],
           2, "is also the file of the model dragon_res4",
           env={"RTRT_MODEL_DIR": os.path.join(WORK, "bench_models")})
with open(os.path.join(WORK, "bench_models", "dragon_vrip_res4.ply.gz"), "rb") as f:
    if f.read() != b"model":
        failures.append("bench -o over its model changed the model file")
# Without a GPU the refusals say what to do instead (a machine without the driver was told its
# driver was too old).
if not os.path.exists("/proc/driver/nvidia/version"):
    expect("bench gpu without a GPU", ["bench", "gpu", "--models", "cube"], 2,
           "(no NVIDIA driver is loaded: no NVIDIA GPU?); rtrt bench cpu times the CPU back end")
    expect("gpus without a GPU", image + ["--gpus", "2"], 2,
           "leave out --gpus to render on the CPU back end")
    expect("farm --local --gpu without a GPU",
           ["farm", "default", "--local", "--gpu", "--frames", "1", "--size", "8x4", "-o",
            "gpu_job"], 2, "--gpu: the CUDA back end: no CUDA device is usable here")

# A manifest or a scene named like one of the frames is refused before any frame (the manifest
# had got frame 1 appended to it, the scene had been written over).
frames = os.path.join(WORK, "frames")
os.makedirs(frames)
scene = os.path.join(frames, "f_0001.ppm")
shutil.copy(os.path.join(WORK, "T.Json"), scene)
play = ["play", "--headless", "--backend", "cpu", "--size", "8x4", "--frames", "3", "-o",
        "frames/f_%04d.ppm"]
expect("manifest over a frame", play + ["default", "--manifest", "frames/f_0002.ppm"], 2,
       "frame 2 would be written over --manifest (frames/f_0002.ppm)")
expect("scene over a frame", play + [scene], 2, "frame 1 would be written over the scene file")
with open(scene) as f:
    if '"instances"' not in f.read():
        failures.append("the scene named like a frame was written over")
if sorted(os.listdir(frames)) != ["f_0001.ppm"]:
    failures.append(f"refused plays left {sorted(os.listdir(frames))}")
os.symlink("frames/f_0001.ppm", os.path.join(WORK, "link.tsv"))
expect("manifest linked to a frame", play + ["default", "--manifest", "link.tsv"], 2,
       "frame 1 would be written over --manifest (link.tsv)")
expect("space-padded frames", ["play", "--headless", "--backend", "cpu", "--size", "8x4",
                               "--frames", "3", "-o", "frames/g%4d.ppm", "default", "--manifest",
                               "frames/g   2.ppm"], 2, "frame 2 would be written over --manifest")
expect("plus sign", image + ["--max-depth", "+3"], 0, "wrote out.ppm")
expect("manifest past the frames", play + ["default", "--manifest", "frames/f_0003.ppm"], 0,
       "wrote frames 0 to 2")

# --record DIR holding an earlier recording's frames is refused before a window opens (a shorter
# recording had left the older one's later frames after its own).
recorded = os.path.join(WORK, "recorded")
os.makedirs(recorded)
open(os.path.join(recorded, "frame_00003.png"), "wb").close()
expect("record over frames", ["play", "default", "--backend", "cpu", "--record", "recorded"], 2,
       "--record: recorded: holds frames of an earlier recording (frame_00003.png)")
expect("report to -", ["bench", "cpu", "--models", "cube", "--output=-"], 2,
       "rtrt writes outputs to files, not to standard output")
if os.path.exists(os.path.join(WORK, "-")):
    failures.append("-o - made a file called -")

# An output naming a file the scene reads (a glTF file's texture) is refused, not written over.
def png_1x1():
    import struct
    import zlib

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(b"\x00\xff\x00\x00")) + chunk(b"IEND", b""))


def textured_triangle():
    import base64
    import json
    import struct
    data = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<6f", 0, 0, 1, 0, 0, 1)
    uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    return json.dumps({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1},
                                    "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}], "images": [{"uri": "texture.png"}],
        "buffers": [{"byteLength": len(data), "uri": uri}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36,
                                                           "byteLength": 24}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}]})


with open(os.path.join(WORK, "texture.png"), "wb") as f:
    f.write(png_1x1())
with open(os.path.join(WORK, "textured.gltf"), "w") as f:
    f.write(textured_triangle())
texture = open(os.path.join(WORK, "texture.png"), "rb").read()
writes_png = run("render", "default", "--backend", "cpu", "--size", "8x4",
                 "-o", "probe.png").returncode == 0
if writes_png:
    expect("output over a glTF texture",
           ["render", "textured.gltf", "--backend", "cpu", "--size", "8x4", "-o", "texture.png"],
           2, "texture.png: is a file of the scene this command read (./texture.png), which "
              "would be written over")
    if open(os.path.join(WORK, "texture.png"), "rb").read() != texture:
        failures.append("the glTF file's texture was written over")
# Formats: one that writes a file without its pixels (JPEG 2000 through OpenImageIO's memory
# writer: its header boxes alone) is refused up front; WebP's 16383-pixel limit is checked
# before the render; the heatmap of a 1-pixel-wide image draws its legend.
if writes_png:
    expect("jp2", ["render", "default", "--backend", "cpu", "--size", "8x4", "-o", "d.jp2"], 2,
           "rtrt cannot write .jp2 images")
    expect("wide webp", ["render", "default", "--backend", "cpu", "--size", "16384x1", "-o",
                         "w.webp"], 2, "WebP images are at most 16383 pixels a side")
expect("narrow heatmap", ["render", "default", "--backend", "cpu", "--size", "1x11", "--view",
                          "heatmap", "-o", "h.ppm"], 0, "wrote h.ppm")
expect("a glTF file with a texture renders", ["render", "textured.gltf", "--backend", "cpu",
                                             "--size", "8x4", "-o", "textured.ppm"], 0, "wrote")

# --frames says what is wrong with a range, in play and farm alike.
headless = ["play", "default", "--headless", "--backend", "cpu", "--size", "8x4", "-o", "p%d.ppm"]
farm = ["farm", "default", "--backend", "cpu", "--size", "8x4", "--dry-run", "-o", "farm_job"]
for command in (headless, farm):
    expect(f"{command[0]} reversed frames", command + ["--frames", "9:3"], 2,
           "A:B renders frames A to B-1, so A must be below B")
    expect(f"{command[0]} frames beyond the limit", command + ["--frames", "10000001"], 2,
           "frames end at 10,000,000 at the latest")
    expect(f"{command[0]} frames far beyond the limit", command + ["--frames", "2:2147483647"],
           2, "frames end at 10,000,000 at the latest")
    # 50,000 digits: refused, not a stack overflow in the pattern matcher.
    expect(f"{command[0]} frames of 50,000 digits", command + ["--frames", "1" * 50000], 2,
           "frames end at 10,000,000 at the latest")
    expect(f"{command[0]} fps of 50,000 digits", command + ["--frames", "1", "--fps", "1" * 50000],
           2, "--fps: expected a number in decimal notation")
    expect(f"{command[0]} no frames", command + ["--frames", "0"], 2,
           "N is how many frames: at least 1")
    expect(f"{command[0]} malformed frames", command + ["--frames", "1-4"], 2,
           "expected N (frames 0 to N-1) or A:B (frames A to B-1)")

# A model asked for whose file is missing is skipped, and the report says so (it had only been
# absent from it); a CPU soak has no GPU spread to report (it had said 0.0).
os.makedirs(os.path.join(WORK, "no_models"), exist_ok=True)
skipped = expect("bench with a model missing",
                 ["bench", "cpu", "--models", "cube,teapot", "--builders", "binned", "--frames",
                  "1", "-o", "cpu.json"], 0, "teapot       skipped:",
                 env={"RTRT_MODEL_DIR": os.path.join(WORK, "no_models")})
if skipped.returncode == 0:
    with open(os.path.join(WORK, "cpu.json")) as f:
        report = json.load(f)
    if [m["model"] for m in report["models"]] != ["cube"] or \
            [m["model"] for m in report.get("skipped", [])] != ["teapot"]:
        failures.append(f"bench with a model missing: report {report.get('skipped')}")
soak = expect("cpu soak", ["bench", "soak", "--backend", "cpu", "--frames", "6", "--every", "2",
                           "--warmup", "1", "--per-frame", "4", "--alive", "8", "-o", "soak.json"],
              0, "flat within 5%")
if soak.returncode == 0:
    with open(os.path.join(WORK, "soak.json")) as f:
        report = json.load(f)
    if report["gpu_spread"] is not None or report["gpu_mib_after_warmup"] != []:
        failures.append(f"cpu soak: gpu_spread {report['gpu_spread']!r}")

if failures:
    sys.exit("\n\n".join(failures))
print("all option-value cases behave")
