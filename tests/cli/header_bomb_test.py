#!/usr/bin/env python3
"""Mesh headers that ask for more than the body can hold, and work beyond the memory there is,
under a bound on address space.

A binary PLY may declare up to one face per byte of its body (an empty index list is one byte),
so its face count passes the check against the body's size; the reader then reserved 12 bytes a
declared face before reading any, and a 2 GiB file of zeros ended in std::bad_alloc (exit 1, no
file or field named). Here a 256 MiB sparse body declares 2^28 faces: that reservation would be
3 GiB, beyond the 2 GiB of address space rtrt is given, and the answer must be exit 2 with the
file and the reason.

usage: header_bomb_test.py RTRT WORK_DIR
"""
import os
import resource
import shutil
import struct
import subprocess
import sys

RTRT, WORK = sys.argv[1], sys.argv[2]
LIMIT = 2 << 30
SKIP = 77  # ctest's SKIP_RETURN_CODE


def bounded():
    resource.setrlimit(resource.RLIMIT_AS, (LIMIT, LIMIT))


def run(*args):
    env = dict(os.environ, RTRT_CACHE_DIR="off")
    return subprocess.run([RTRT, *args], capture_output=True, text=True, preexec_fn=bounded,
                          env=env, timeout=300)


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
# A sanitizer build reserves its shadow memory up front and cannot start under the bound.
if run("--version").returncode != 0:
    print("rtrt does not start with 2 GiB of address space (a sanitizer build?): skipped")
    sys.exit(SKIP)

faces = 1 << 28
header = ("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
          "property float y\nproperty float z\nelement face %d\n"
          "property list uchar int vertex_indices\nend_header\n" % faces).encode()
vertices = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
path = os.path.join(WORK, "face_bomb.ply")
with open(path, "wb") as f:
    f.write(header + vertices)
    f.truncate(len(header) + len(vertices) + faces)  # a sparse body of empty face lists

for command in (["info", path], ["convert", path, "-o", os.path.join(WORK, "out.rtmodel")]):
    r = run(*command)
    expected = "rtrt: error: %s: contains no triangles" % path
    if r.returncode != 2 or expected not in r.stderr:
        sys.exit("rtrt %s: status %d, expected 2 and '%s':\n%s" %
                 (command[0], r.returncode, expected, r.stderr))
    print("rtrt %s: ok (%s)" % (command[0], r.stderr.strip()))
if os.path.exists(os.path.join(WORK, "out.rtmodel")):
    sys.exit("convert wrote out.rtmodel although it failed")

# Work that needs more memory than the bound is exit 1 in words ("std::bad_alloc" said neither
# the cause nor what to do), and writes nothing.
big = os.path.join(WORK, "big.png")
r = run("render", "--size", "16384x16384", "--backend", "cpu", "-o", big)
if r.returncode != 1 or "rtrt: error: out of memory: " not in r.stderr or os.path.exists(big):
    sys.exit("rtrt render 16384x16384 in 2 GiB: status %d, expected 1 and 'out of memory':\n%s"
             % (r.returncode, r.stderr))
print("rtrt render beyond the memory bound: ok (%s)" % r.stderr.strip())
shutil.rmtree(WORK)
