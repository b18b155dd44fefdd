#!/usr/bin/env python3
"""Writes assets/models/textured_quads.gltf: three quads with one 8x8 texture under the three
wrap modes (repeat + nearest, mirrored repeat + linear, clamp + linear), texture coordinates
from -0.5 to 1.5 so that every wrap shows, an untextured floor, a point and a directional light
(KHR_lights_punctual), a camera, and an animation that turns the middle quad (LINEAR rotation)
and moves the right one (STEP translation). The GPU-vs-CPU tests and assets/scenes/gltf_demo.json
use it. Self-contained: the buffer and the PNG image are base64 data URIs."""
import base64, json, math, os, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_writer import GltfBuffer, png  # noqa: E402 (after the path)

texels = [[((x * 37 + y * 11) % 256, (255 - x * 32) % 256, (y * 32 + 16) % 256) if (x + y) % 2 == 0
           else (240, 240 - 20 * y, 30 + 25 * x) for x in range(8)] for y in range(8)]
image = png(8, 8, texels)

buffer = GltfBuffer()
add, views, accessors = buffer.add, buffer.views, buffer.accessors

quad_pos = add("f", [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0], "VEC3", 4,
               minmax=([-1, -1, 0], [1, 1, 0]))
quad_nrm = add("f", [0, 0, 1] * 4, "VEC3", 4)
quad_uv = add("f", [-0.5, 1.5, 1.5, 1.5, 1.5, -0.5, -0.5, -0.5], "VEC2", 4)
quad_idx = add("H", [0, 1, 2, 0, 2, 3], "SCALAR", 6, component=5123)
floor_pos = add("f", [-6, 0, -4, 6, 0, -4, 6, 0, 4, -6, 0, 4], "VEC3", 4,
                minmax=([-6, 0, -4], [6, 0, 4]))
floor_idx = add("B", [0, 2, 1, 0, 3, 2], "SCALAR", 6, component=5121)
times = add("f", [0, 1, 2], "SCALAR", 3, minmax=([0], [2]))
s = math.sqrt(0.5)
turns = add("f", [0, 0, 0, 1, 0, s, 0, s, 0, 1, 0, 0], "VEC4", 3)
steps = add("f", [2.6, 1.2, 0, 2.6, 1.6, 0, 2.6, 1.2, 0], "VEC3", 3)

doc = {
    "asset": {"version": "2.0", "generator": "rtrt tools/make_textured_gltf.py"},
    "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1, 0.9, 0.8], "intensity": 0.6},
        {"type": "directional", "color": [1, 1, 1], "intensity": 0.5}]}},
    "buffers": buffer.buffers(),
    "bufferViews": views, "accessors": accessors,
    "images": [{"uri": "data:image/png;base64," + base64.b64encode(image).decode()}],
    "samplers": [{"magFilter": 9728, "minFilter": 9728, "wrapS": 10497, "wrapT": 10497},
                 {"magFilter": 9729, "minFilter": 9729, "wrapS": 33648, "wrapT": 33648},
                 {"magFilter": 9729, "minFilter": 9729, "wrapS": 33071, "wrapT": 33071}],
    "textures": [{"source": 0, "sampler": i} for i in range(3)],
    "materials": [{"name": name, "pbrMetallicRoughness": {
                      "baseColorTexture": {"index": i}, "metallicFactor": 0, "roughnessFactor": 0.6}}
                  for i, name in enumerate(["repeat_nearest", "mirror_linear", "clamp_linear"])] +
                 [{"name": "floor", "pbrMetallicRoughness": {
                      "baseColorFactor": [0.6, 0.6, 0.65, 1], "metallicFactor": 0.2, "roughnessFactor": 0.3}}],
    "meshes": [{"name": "quad%d" % i, "primitives": [{"attributes": {
                    "POSITION": quad_pos, "NORMAL": quad_nrm, "TEXCOORD_0": quad_uv},
                    "indices": quad_idx, "material": i}]} for i in range(3)] +
              [{"name": "floor", "primitives": [{"attributes": {"POSITION": floor_pos},
                                                 "indices": floor_idx, "material": 3}]}],
    "cameras": [{"type": "perspective",
                 "perspective": {"yfov": 0.7, "aspectRatio": 1.5, "znear": 0.1}}],
    "nodes": [
        {"name": "quads", "translation": [0, 0, 0], "children": [1, 2, 3]},
        {"name": "left", "mesh": 0, "translation": [-2.6, 1.2, 0]},
        {"name": "middle", "mesh": 1, "translation": [0, 1.2, 0]},
        {"name": "right", "mesh": 2, "translation": [2.6, 1.2, 0]},
        {"name": "floor", "mesh": 3},
        {"name": "camera", "camera": 0, "translation": [0, 2.2, 8.5],
         "rotation": [-0.06, 0, 0, 0.9982]},
        {"name": "lamp", "translation": [0, 4, 4],
         "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "sun", "rotation": [-0.3826834, 0.3, 0, 0.8733],
         "extensions": {"KHR_lights_punctual": {"light": 1}}},
    ],
    "scenes": [{"nodes": [0, 4, 5, 6, 7]}], "scene": 0,
    "animations": [{"name": "turn", "samplers": [
        {"input": times, "output": turns, "interpolation": "LINEAR"},
        {"input": times, "output": steps, "interpolation": "STEP"}],
        "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}},
                     {"sampler": 1, "target": {"node": 3, "path": "translation"}}]}],
}
out = sys.argv[1] if len(sys.argv) > 1 else "assets/models/textured_quads.gltf"
with open(out, "w") as f:
    json.dump(doc, f, indent=1)
    f.write("\n")
