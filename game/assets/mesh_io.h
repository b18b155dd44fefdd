#pragma once
// Triangle-mesh loaders for real models: Wavefront OBJ and Stanford PLY (ASCII or binary, plain or
// gzip-compressed).
#include <cstdint>
#include <string>

#include "engine/geometry/triangle_mesh.h"

namespace rtrt {

// Loads PATH by its extension (any case): .obj, .ply or .ply.gz. Convex polygons are fans from
// their first corner, concave ones ear-clipped (polygon_triangulation.h), PLY triangle strips
// (tristrips) unrolled, and triangles with a repeated vertex index dropped. A vertex or face
// corner takes its normal from the file where it has one with a direction, otherwise the
// area-weighted normal of the faces around its vertex (engine/geometry/smooth_normals.h). Throws
// InputError naming the file, the field ("vertex 12", "face 7", "line 33", "header line 4") and
// the reason for a missing or unreadable file, an unknown extension, a malformed or truncated file,
// non-finite coordinates, out-of-range indices or a mesh without triangles.
// fileVertices, where given, receives the file's vertex count (an OBJ's `v` statements, a PLY's
// vertex element), which is what a model's "source vertices" are.
TriangleMesh LoadMesh(const std::string& path, uint64_t* fileVertices = nullptr);

}  // namespace rtrt
