#pragma once
// Triangle-mesh loaders for real models: Wavefront OBJ and Stanford PLY (ASCII or binary, plain or
// gzip-compressed).
#include <string>

#include "engine/geometry/triangle_mesh.h"

namespace rtrt {

// Loads PATH by its extension (any case): .obj, .ply or .ply.gz. Polygons are fan-triangulated and
// faces with a repeated vertex index dropped. Normals come from the file when it gives one for
// every vertex (PLY) or every face corner (OBJ), otherwise from ComputeSmoothNormals
// (engine/geometry/smooth_normals.h). Throws
// InputError naming the file, the field ("vertex 12", "face 7", "line 33", "header line 4") and
// the reason for a missing or unreadable file, an unknown extension, a malformed or truncated file,
// non-finite coordinates, out-of-range indices or a mesh without triangles.
TriangleMesh LoadMesh(const std::string& path);

}  // namespace rtrt
