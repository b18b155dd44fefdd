#!/usr/bin/env python3
"""Writes assets/models/pbr_showcase.gltf: glTF's metallic-roughness material as authors use it.
Two rows of five spheres (dielectric red and gold metal, roughness 0 to 1), an emissive sphere
with an emissive texture, and a tiled floor with every texture slot: base colour (sRGB),
metallic-roughness, a normal map with bevelled tiles, occlusion in the grout, all repeated by
KHR_texture_transform. Lights in physical units (KHR_lights_punctual): a sun of 2,000 lux, a spot
of 3,000 cd and a point light of 400 cd. The GPU-vs-CPU tests, the README's pictures and
assets/scenes/pbr_showcase.json use it. Self-contained: buffer and PNG images are data URIs."""
import base64, json, math, os, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_writer import GltfBuffer, png  # noqa: E402 (after the path)

N = 64  # texture size: 4 x 4 tiles of 16 texels, 2 of them grout
def tile(x, y):  # (distance to the tile's left/right/top/bottom edge in texels, grout?)
    fx, fy = x % 16, y % 16
    return fx, fy, fx < 2 or fy < 2

def clamp8(v):
    return max(0, min(255, int(round(v))))

base, mr, normal, occlusion, glow = [], [], [], [], []
for y in range(N):
    rb, rm, rn, ro, rg = [], [], [], [], []
    for x in range(N):
        fx, fy, grout = tile(x, y)
        shade = ((x // 16) * 7 + (y // 16) * 13) % 5
        rb.append((90, 88, 85) if grout else (150 + 12 * shade, 70 + 6 * shade, 50))
        # roughness in green, metalness in blue: matte grout, tiles smoother
        rm.append((0, 255, 0) if grout else (0, 110 + 15 * shade, 0))
        # bevels two texels wide at each tile edge: +x of the map is +u, +y is the image's up
        nx = ny = 0.0
        if not grout:
            if fx < 4: nx = -0.5
            elif fx > 13: nx = 0.5
            if fy < 4: ny = 0.5
            elif fy > 13: ny = -0.5
        nz = math.sqrt(max(0.0, 1 - nx * nx - ny * ny))
        rn.append((clamp8((nx * 0.5 + 0.5) * 255), clamp8((ny * 0.5 + 0.5) * 255),
                   clamp8((nz * 0.5 + 0.5) * 255)))
        ro.append((90, 90, 90) if grout else (255, 255, 255))
        rg.append((255, 200, 80) if (x // 8 + y // 8) % 2 == 0 else (20, 10, 0))
    for row, r in ((base, rb), (mr, rm), (normal, rn), (occlusion, ro), (glow, rg)):
        row.append(r)
images = [png(N, N, img) for img in (base, mr, normal, occlusion, glow)]

buffer = GltfBuffer()
add, views, accessors = buffer.add, buffer.views, buffer.accessors

# A UV sphere of radius 0.5: 48 segments, 24 rings; u around, v from the top down.
seg, rings = 48, 24
pos, nrm, uv, idx = [], [], [], []
for r in range(rings + 1):
    theta = math.pi * r / rings
    for s_ in range(seg + 1):
        phi = 2 * math.pi * s_ / seg
        n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
        pos += [0.5 * c for c in n]
        nrm += list(n)
        uv += [s_ / seg, r / rings]
for r in range(rings):
    for s_ in range(seg):
        a, b = r * (seg + 1) + s_, (r + 1) * (seg + 1) + s_
        if r > 0: idx += [a, b, a + 1]
        if r < rings - 1: idx += [a + 1, b, b + 1]
sphere_pos = add("f", pos, "VEC3", len(pos) // 3, minmax=([-0.5] * 3, [0.5] * 3))
sphere_nrm = add("f", nrm, "VEC3", len(nrm) // 3)
sphere_uv = add("f", uv, "VEC2", len(uv) // 2)
sphere_idx = add("H", idx, "SCALAR", len(idx), component=5123)
floor_pos = add("f", [-5, 0, -3, 5, 0, -3, 5, 0, 3, -5, 0, 3], "VEC3", 4,
                minmax=([-5, 0, -3], [5, 0, 3]))
floor_nrm = add("f", [0, 1, 0] * 4, "VEC3", 4)
floor_uv = add("f", [0, 0, 1, 0, 1, 0.6, 0, 0.6], "VEC2", 4)
floor_idx = add("B", [0, 2, 1, 0, 3, 2], "SCALAR", 6, component=5121)

tiles = {"KHR_texture_transform": {"scale": [5, 5], "offset": [0.1, 0], "rotation": 0.0}}
materials = []
for row, (name, colour, metal) in enumerate([("red plastic", [0.8, 0.05, 0.04, 1], 0.0),
                                             ("gold", [1.0, 0.78, 0.34, 1], 1.0)]):
    for i in range(5):
        materials.append({"name": "%s, roughness %.2f" % (name, i / 4), "pbrMetallicRoughness": {
            "baseColorFactor": colour, "metallicFactor": metal, "roughnessFactor": i / 4}})
materials.append({"name": "glow", "pbrMetallicRoughness": {
                      "baseColorFactor": [0.05, 0.05, 0.05, 1], "metallicFactor": 0, "roughnessFactor": 0.5},
                  "emissiveTexture": {"index": 4}, "emissiveFactor": [1, 1, 1],
                  "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 600}}})
materials.append({"name": "tiles", "pbrMetallicRoughness": {
                      "baseColorTexture": {"index": 0, "extensions": tiles},
                      "metallicRoughnessTexture": {"index": 1, "extensions": tiles},
                      "metallicFactor": 1.0, "roughnessFactor": 1.0},
                  "normalTexture": {"index": 2, "scale": 1.0, "extensions": tiles},
                  "occlusionTexture": {"index": 3, "strength": 1.0, "extensions": tiles}})

def sphere_mesh(material):
    return {"primitives": [{"attributes": {"POSITION": sphere_pos, "NORMAL": sphere_nrm,
                                           "TEXCOORD_0": sphere_uv},
                            "indices": sphere_idx, "material": material}]}

nodes = []
for m in range(10):
    nodes.append({"name": materials[m]["name"], "mesh": m,
                  "translation": [-2.4 + 1.2 * (m % 5), 0.5, 0.7 - 1.4 * (m // 5)]})
nodes.append({"name": "glow", "mesh": 10, "translation": [2.9, 0.5, 1.9]})
nodes.append({"name": "floor", "mesh": 11})
nodes.append({"name": "camera", "camera": 0, "translation": [0, 3.4, 6.0],
              "rotation": [-0.2588190, 0, 0, 0.9659258]})
# the sun comes from the upper left, behind the camera; the spot shines down on the gold row
nodes.append({"name": "sun", "rotation": [-0.4545195, -0.2432103, -0.1330222, 0.8463112],
              "extensions": {"KHR_lights_punctual": {"light": 0}}})
nodes.append({"name": "spot", "translation": [0.0, 4.0, -0.7], "rotation": [-0.7071068, 0, 0, 0.7071068],
              "extensions": {"KHR_lights_punctual": {"light": 1}}})
nodes.append({"name": "lamp", "translation": [-3.5, 1.5, 2.0],
              "extensions": {"KHR_lights_punctual": {"light": 2}}})

doc = {
    "asset": {"version": "2.0", "generator": "rtrt tools/make_pbr_gltf.py"},
    "extensionsUsed": ["KHR_lights_punctual", "KHR_texture_transform",
                       "KHR_materials_emissive_strength"],
    "extensions": {"KHR_lights_punctual": {"lights": [
        {"type": "directional", "color": [1, 0.96, 0.9], "intensity": 2000},
        {"type": "spot", "color": [1, 1, 1], "intensity": 3000, "range": 20,
         "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.6}},
        {"type": "point", "color": [0.6, 0.75, 1.0], "intensity": 400}]}},
    "buffers": buffer.buffers(),
    "bufferViews": views, "accessors": accessors,
    "images": [{"uri": "data:image/png;base64," + base64.b64encode(i).decode()} for i in images],
    "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}],
    "textures": [{"source": i, "sampler": 0} for i in range(5)],
    "materials": materials,
    "meshes": [sphere_mesh(m) for m in range(11)] +
              [{"primitives": [{"attributes": {"POSITION": floor_pos, "NORMAL": floor_nrm,
                                               "TEXCOORD_0": floor_uv},
                                "indices": floor_idx, "material": 11}]}],
    "cameras": [{"type": "perspective",
                 "perspective": {"yfov": 0.75, "aspectRatio": 16 / 9, "znear": 0.1}}],
    "nodes": nodes,
    "scenes": [{"nodes": list(range(len(nodes)))}], "scene": 0,
}
out = sys.argv[1] if len(sys.argv) > 1 else "assets/models/pbr_showcase.gltf"
with open(out, "w") as f:
    json.dump(doc, f, separators=(",", ":"))
    f.write("\n")
