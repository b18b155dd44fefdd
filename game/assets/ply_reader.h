#pragma once
// Stanford PLY (Turk 1994): a text header of elements and typed properties, then the data.
#include <string>
#include <string_view>

#include "engine/geometry/triangle_mesh.h"

namespace rtrt {

// Stanford PLY data, ASCII or binary (already decompressed), as a triangle mesh (LoadMesh's
// rules, mesh_io.h); PATH names the file in messages ("vertex 12", "header line 4").
TriangleMesh ParsePly(const std::string& path, std::string_view data);

}  // namespace rtrt
