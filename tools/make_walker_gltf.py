#!/usr/bin/env python3
"""Writes assets/models/walker.gltf: a skinned humanoid about 1.8 tall standing on y = 0 and
facing +z, for the crowd benchmark (about 4,000 triangles, one mesh, one primitive, one
material). Pelvis-to-chest torso, neck, head, and arms and legs as one tapered capsule per
limb, each tessellated finely enough to bend smoothly at elbow and knee; foot blocks. A skin of
17 joints (hips -> spine -> chest -> neck -> head; chest -> shoulder -> upper arm -> forearm;
hips -> thigh -> shin -> foot) with at most two influences per vertex, blended across each
joint. One 1 s looping walk cycle in place: thighs and shins CUBICSPLINE rotations, the rest
LINEAR (hip bob translation, pelvis and torso twist, arm swing, feet), and a LINEAR `weights`
channel on a "breathing" morph target that swells the chest (POSITION and NORMAL deltas).
The mesh node and the skeleton root are siblings under one scene root, as exporters write
them. Self-contained: the buffer is a base64 data URI."""
import json, math, os, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_writer import GltfBuffer  # noqa: E402 (after the path)

SEGMENTS = 16  # around every capsule: enough that silhouettes and normals read round

# Joints: name, parent index, bind position in the model's frame. The bind pose has no
# rotations, so each joint's global bind transform is a pure translation (see inverse binds).
JOINTS = [
    ("hips", -1, (0, 0.95, 0)), ("spine", 0, (0, 1.08, 0)), ("chest", 1, (0, 1.28, 0)),
    ("neck", 2, (0, 1.50, 0)), ("head", 3, (0, 1.58, 0)),
    ("shoulder_L", 2, (0.09, 1.44, 0)), ("upperarm_L", 5, (0.20, 1.42, 0)),
    ("forearm_L", 6, (0.23, 1.15, 0)),
    ("shoulder_R", 2, (-0.09, 1.44, 0)), ("upperarm_R", 8, (-0.20, 1.42, 0)),
    ("forearm_R", 9, (-0.23, 1.15, 0)),
    ("thigh_L", 0, (0.10, 0.92, 0)), ("shin_L", 11, (0.10, 0.50, 0)),
    ("foot_L", 12, (0.10, 0.09, 0)),
    ("thigh_R", 0, (-0.10, 0.92, 0)), ("shin_R", 14, (-0.10, 0.50, 0)),
    ("foot_R", 15, (-0.10, 0.09, 0)),
]
J = {name: i for i, (name, _, _) in enumerate(JOINTS)}

def sub(a, b): return [a[i] - b[i] for i in range(3)]
def add3(a, b): return [a[i] + b[i] for i in range(3)]
def scale(a, s): return [x * s for x in a]
def dot(a, b): return sum(a[i] * b[i] for i in range(3))
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0]]
def norm(a):
    l = math.sqrt(dot(a, a))
    return scale(a, 1 / l) if l > 0 else [0, 0, 0]
def smoothstep(x): x = min(1, max(0, x)); return x * x * (3 - 2 * x)

positions, skin, part, triangles = [], [], [], []  # skin: [(joint, weight), ...] per vertex

def capsule(a, b, profile, bones, name, squash=1.0):
    """A surface of revolution around the segment a -> b. profile: (h, r) pairs, h the distance
    along the axis from a (negative below a), r the radius (0 makes a single pole vertex).
    bones: (h, joint, blend) in increasing h: from each h on the vertex follows that joint,
    cross-faded over +-blend, so a vertex has at most two influences and the crease at a
    joint is spread over several rings rather than folding at one. squash scales the second
    perpendicular axis (elliptic torso)."""
    d = norm(sub(b, a))
    u = norm(sub([1, 0, 0], scale(d, d[0]))) if abs(d[0]) < 0.9 else [0, 0, 1]
    v = cross(d, u)  # (u, v, d) right-handed, so the winding below faces outward
    rings = []
    for h, r in profile:
        w = [(bones[0][1], 1.0)]
        for bh, joint, blend in bones[1:]:
            t = smoothstep((h - bh + blend) / (2 * blend))
            if t >= 1: w = [(joint, 1.0)]
            elif t > 0: w = [(w[0][0], 1 - t), (joint, t)]
        centre = add3(a, scale(d, h))
        count = 1 if r == 0 else SEGMENTS
        ring = []
        for j in range(count):
            phi = 2 * math.pi * j / SEGMENTS
            ring.append(len(positions))
            positions.append(add3(centre, add3(scale(u, r * math.cos(phi)),
                                               scale(v, r * squash * math.sin(phi)))))
            skin.append(w)
            part.append(name)
        rings.append(ring)
    for lo, hi in zip(rings, rings[1:]):
        for j in range(SEGMENTS):
            i00, i01 = lo[j % len(lo)], lo[(j + 1) % len(lo)]
            i10, i11 = hi[j % len(hi)], hi[(j + 1) % len(hi)]
            for tri in ((i00, i01, i11), (i00, i11, i10)):
                if len(set(tri)) == 3: triangles.append(tri)  # skip a pole's collapsed half

def capsule_profile(length, r0, r1, cap_rings=4, body_rings=10):
    """Hemisphere of radius r0 around h = 0, a taper to r1, hemisphere of r1 around h = length:
    caps centred on the joints make ball joints that keep their shape as the limb turns."""
    step = math.pi / 2 / cap_rings
    prof = [(-r0 * math.cos(step * i), r0 * math.sin(step * i)) for i in range(cap_rings)]
    prof += [(length * i / body_rings, r0 + (r1 - r0) * i / body_rings)
             for i in range(body_rings + 1)]
    prof += [(length + r1 * math.sin(step * i), r1 * math.cos(step * i))
             for i in range(1, cap_rings + 1)]
    return prof

def box(lo, hi, joint, name):
    """A foot block: 24 vertices so each face keeps its own flat normal."""
    for axis in range(3):
        for side in (0, 1):
            n = [0, 0, 0]; n[axis] = 1 if side else -1
            a1, a2 = (axis + 1) % 3, (axis + 2) % 3
            base = len(positions)
            for s1, s2 in ((0, 0), (1, 0), (1, 1), (0, 1)):
                p = [0, 0, 0]
                p[axis] = hi[axis] if side else lo[axis]
                p[a1] = hi[a1] if s1 else lo[a1]
                p[a2] = hi[a2] if s2 else lo[a2]
                positions.append(p); skin.append([(joint, 1.0)]); part.append(name)
            quad = (base, base + 1, base + 2, base + 3)
            # (a1, a2, axis) is right-handed, so a1 -> a2 winds counter-clockwise about +axis.
            tris = [(quad[0], quad[1], quad[2]), (quad[0], quad[2], quad[3])]
            if not side: tris = [(t[0], t[2], t[1]) for t in tris]
            triangles.extend(tris)

def pos(name): return list(JOINTS[J[name]][2])

# Torso from crotch to neck base: pelvis (hips), waist (spine), ribcage (chest); elliptic.
torso = [(0.0, 0.0), (0.015, 0.07), (0.04, 0.115), (0.08, 0.145), (0.13, 0.155), (0.19, 0.145),
         (0.25, 0.13), (0.31, 0.125), (0.37, 0.14), (0.43, 0.16), (0.49, 0.17), (0.54, 0.17),
         (0.58, 0.16), (0.61, 0.14), (0.635, 0.11), (0.65, 0.07), (0.655, 0.0)]
capsule([0, 0.84, 0], [0, 1.6, 0], torso,
        [(0, J["hips"], 0), (1.08 - 0.84, J["spine"], 0.06), (1.28 - 0.84, J["chest"], 0.07)],
        "torso", squash=0.65)
capsule([0, 1.44, 0], [0, 1.62, 0], capsule_profile(0.18, 0.05, 0.05, 3, 6),
        [(0, J["chest"], 0), (0.06, J["neck"], 0.03), (0.14, J["head"], 0.03)], "neck")
head = [(-0.115 * math.cos(math.pi * i / 10), 0.105 * math.sin(math.pi * i / 10))
        for i in range(11)]
capsule([0, 1.685, 0.01], [0, 1.8, 0.01], head, [(0, J["head"], 0)], "head", squash=1.1)
capsule([0, 1.665, 0.1], [0, 1.665, 0.13], capsule_profile(0.03, 0.02, 0.018, 3, 1),
        [(0, J["head"], 0)], "nose")
for side in "LR":
    s = 1 if side == "L" else -1  # the figure's left is +x: it faces +z
    shoulder, elbow = pos("upperarm_" + side), pos("forearm_" + side)
    wrist = add3(elbow, [s * 0.01, -0.25, 0.01])
    arm = capsule_profile(0.52, 0.055, 0.038, 4, 12)
    capsule(shoulder, wrist, arm, [(-1, J["shoulder_" + side], 0),
                                  (0.0, J["upperarm_" + side], 0.05),
                                  (0.27, J["forearm_" + side], 0.05)], "arm")
    hip, knee, ankle = pos("thigh_" + side), pos("shin_" + side), pos("foot_" + side)
    leg = capsule_profile(0.83, 0.085, 0.045, 4, 14)
    capsule(hip, ankle, leg, [(-1, J["hips"], 0), (0.0, J["thigh_" + side], 0.05),
                              (0.42, J["shin_" + side], 0.06), (0.83, J["foot_" + side], 0.03)],
            "leg")
    box([ankle[0] - 0.05, 0.0, -0.06], [ankle[0] + 0.05, 0.075, 0.17], J["foot_" + side], "foot")

def vertex_normals(points):
    """Area-weighted sum of the adjacent faces' normals: smooth across every ring and the seam
    (rings share their first vertex), flat on the feet (their faces share no vertices)."""
    acc = [[0, 0, 0] for _ in points]
    for a, b, c in triangles:
        n = cross(sub(points[b], points[a]), sub(points[c], points[a]))
        for i in (a, b, c): acc[i] = add3(acc[i], n)
    return [norm(n) for n in acc]

normals = vertex_normals(positions)

# Morph target "breathe": the ribcage swells, the front most, fading out above and below.
# NORMAL deltas are the breathed surface's normals less the rest ones, so shading follows.
breathed = []
for p, name in zip(positions, part):
    swell = math.sin(math.pi * min(1, max(0, (p[1] - 1.12) / 0.34))) ** 2 if name == "torso" else 0
    breathed.append([p[0] * (1 + 0.08 * swell), p[1],
                     p[2] * (1 + (0.18 if p[2] > 0 else 0.06) * swell)])
breathe_pos = [sub(b, p) for b, p in zip(breathed, positions)]
breathe_nrm = [sub(m, n) if name == "torso" else [0, 0, 0]
               for m, n, name in zip(vertex_normals(breathed), normals, part)]

# Walk cycle: phase p = 2 pi t over 1 s. Rotations about x: positive swings the limb's far end
# backward (-z), since the limbs hang along -y. Left leg forward at p = pi/2, back at 3 pi/2;
# each arm swings against its leg; a knee folds most as its thigh passes under the hip.
def axis_angle(axis, angle):
    s = math.sin(angle / 2)
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle / 2)]

def qmul(a, b):
    return [a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
            a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
            a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
            a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]]

X, Y, Z = [1, 0, 0], [0, 1, 0], [0, 0, 1]
def thigh(p, s): return 0.38 * s * -math.sin(p)
def bump(x, k): return (0.5 + 0.5 * math.cos(x)) ** k  # periodic, peaks at x = 0
def knee(p, s):  # a small flex after heel strike, a large one in the swing forward
    p += 0 if s > 0 else math.pi
    return 0.05 + 0.15 * bump(p - 0.8 * math.pi, 4) + 0.95 * bump(p - 1.95 * math.pi, 3)
ROT = {  # joint -> rotation at phase p, as a quaternion (x, y, z, w)
    "thigh_L": lambda p: axis_angle(X, thigh(p, 1)),
    "thigh_R": lambda p: axis_angle(X, thigh(p, -1)),
    "shin_L": lambda p: axis_angle(X, knee(p, 1)),
    "shin_R": lambda p: axis_angle(X, knee(p, -1)),
    # Feet stay near level: undo most of the leg's pitch, tipping the toe up at heel strike.
    "foot_L": lambda p: axis_angle(X, -0.8 * (thigh(p, 1) + knee(p, 1))),
    "foot_R": lambda p: axis_angle(X, -0.8 * (thigh(p, -1) + knee(p, -1))),
    "hips": lambda p: qmul(axis_angle(Y, -0.09 * math.sin(p)), axis_angle(Z, 0.03 * math.cos(p))),
    "spine": lambda p: axis_angle(Y, 0.08 * math.sin(p)),
    "chest": lambda p: qmul(axis_angle(Y, 0.12 * math.sin(p)), axis_angle(X, 0.05)),
    "head": lambda p: axis_angle(Y, -0.1 * math.sin(p)),
    "upperarm_L": lambda p: qmul(axis_angle(X, 0.4 * math.sin(p)), axis_angle(Z, 0.08)),
    "upperarm_R": lambda p: qmul(axis_angle(X, -0.4 * math.sin(p)), axis_angle(Z, -0.08)),
    "forearm_L": lambda p: axis_angle(X, -0.3 - 0.25 * (0.5 - 0.5 * math.sin(p))),
    "forearm_R": lambda p: axis_angle(X, -0.3 - 0.25 * (0.5 + 0.5 * math.sin(p))),
}
CUBIC = {"thigh_L", "thigh_R", "shin_L", "shin_R"}
# Hips lowest at double support (p = pi/2, 3 pi/2), when the legs are spread.
def hips_translation(p): return [0, 0.95 - 0.012 + 0.012 * math.cos(2 * p), 0]
def breath(p): return 0.5 - 0.5 * math.cos(p)

# --- Buffer ---
buffer = GltfBuffer()
add, views, accessors = buffer.add, buffer.views, buffer.accessors

def vec3s(values, minmax=False):
    bounds = ([min(v[i] for v in values) for i in range(3)],
              [max(v[i] for v in values) for i in range(3)]) if minmax else None
    return add("f", [c for v in values for c in v], "VEC3", len(values), minmax=bounds,
               target=34962)

nv = len(positions)
pos_acc = vec3s(positions, minmax=True)
nrm_acc = vec3s(normals)
joints = [[j for j, _ in w] + [0] * (4 - len(w)) for w in skin]
weights = [[x for _, x in w] + [0.0] * (4 - len(w)) for w in skin]
jnt_acc = add("B", [c for v in joints for c in v], "VEC4", nv, component=5121, target=34962)
wgt_acc = add("f", [c for v in weights for c in v], "VEC4", nv, target=34962)
idx_acc = add("H", [i for t in triangles for i in t], "SCALAR", 3 * len(triangles),
              component=5123, target=34963)
# POSITION deltas of a morph target must give their min and max (glTF 2.0, "Morph Targets").
morph_pos = vec3s(breathe_pos, minmax=True)
morph_nrm = vec3s(breathe_nrm)
# inverseBindMatrices: the inverse of each joint's global bind transform. The scene root and
# the mesh node are identities and the bind pose has no rotations, so a joint's global bind
# transform is the translation to its bind position and its inverse the translation back:
# skinning then maps a vertex into the joint's frame and out along the joint's animated pose.
ibm = []
for _, _, p in JOINTS:
    ibm += [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -p[0], -p[1], -p[2], 1]  # column-major
ibm_acc = add("f", ibm, "MAT4", len(JOINTS))

# Keys: LINEAR every 1/16 s; CUBICSPLINE every 1/8 s with tangents from the analytic curve's
# time derivative (per second, as the spec's Hermite form wants), so the spline is smooth and,
# the first and last keys being equal, so is the loop.
DURATION, LINEAR_KEYS, CUBIC_KEYS, EPS = 1.0, 16, 8, 1e-4
def times(n): return add("f", [DURATION * k / n for k in range(n + 1)], "SCALAR", n + 1,
                         minmax=([0], [DURATION]))
linear_t, cubic_t = times(LINEAR_KEYS), times(CUBIC_KEYS)
def phase(t): return 2 * math.pi * t / DURATION
samplers, channels = [], []
def channel(node, path, f, cubic, width):
    if cubic:
        out = []
        for k in range(CUBIC_KEYS + 1):
            t = DURATION * k / CUBIC_KEYS
            tangent = [(a - b) / (2 * EPS) for a, b in zip(f(phase(t + EPS)), f(phase(t - EPS)))]
            out += tangent + f(phase(t)) + tangent
        count = 3 * (CUBIC_KEYS + 1)
    else:
        out = [c for k in range(LINEAR_KEYS + 1) for c in f(phase(DURATION * k / LINEAR_KEYS))]
        count = LINEAR_KEYS + 1
    out_acc = add("f", out, {4: "VEC4", 3: "VEC3", 1: "SCALAR"}[width], count)
    samplers.append({"input": cubic_t if cubic else linear_t, "output": out_acc,
                     "interpolation": "CUBICSPLINE" if cubic else "LINEAR"})
    channels.append({"sampler": len(samplers) - 1, "target": {"node": node, "path": path}})

JOINT_NODE0 = 2  # nodes: 0 scene root, 1 mesh, then the joints in JOINTS order
for name, f in ROT.items():
    channel(JOINT_NODE0 + J[name], "rotation", f, name in CUBIC, 4)
channel(JOINT_NODE0 + J["hips"], "translation", hips_translation, False, 3)
channel(1, "weights", lambda p: [breath(p)], False, 1)

nodes = [{"name": "walker", "children": [1, JOINT_NODE0]},
         {"name": "body", "mesh": 0, "skin": 0}]
for i, (name, parent, p) in enumerate(JOINTS):
    origin = JOINTS[parent][2] if parent >= 0 else (0, 0, 0)
    node = {"name": name, "translation": [round(p[k] - origin[k], 6) for k in range(3)]}
    children = [JOINT_NODE0 + c for c, (_, cp, _) in enumerate(JOINTS) if cp == i]
    if children: node["children"] = children
    nodes.append(node)

doc = {
    "asset": {"version": "2.0", "generator": "rtrt tools/make_walker_gltf.py"},
    "buffers": buffer.buffers(),
    "bufferViews": views, "accessors": accessors,
    "materials": [{"name": "walker", "pbrMetallicRoughness": {
        "baseColorFactor": [0.75, 0.45, 0.3, 1], "metallicFactor": 0, "roughnessFactor": 0.55}}],
    "meshes": [{"name": "walker", "weights": [0], "extras": {"targetNames": ["breathe"]},
                "primitives": [{"attributes": {"POSITION": pos_acc, "NORMAL": nrm_acc,
                                               "JOINTS_0": jnt_acc, "WEIGHTS_0": wgt_acc},
                                "indices": idx_acc, "material": 0,
                                "targets": [{"POSITION": morph_pos, "NORMAL": morph_nrm}]}]}],
    "skins": [{"name": "walker", "inverseBindMatrices": ibm_acc, "skeleton": JOINT_NODE0,
               "joints": [JOINT_NODE0 + i for i in range(len(JOINTS))]}],
    "nodes": nodes,
    "scenes": [{"nodes": [0]}], "scene": 0,
    "animations": [{"name": "walk", "samplers": samplers, "channels": channels}],
}
out = sys.argv[1] if len(sys.argv) > 1 else "assets/models/walker.gltf"
with open(out, "w") as f:
    json.dump(doc, f, indent=1)
    f.write("\n")
print("%s: %d triangles, %d vertices, %d joints, %d channels" %
      (out, len(triangles), nv, len(JOINTS), len(channels)))
