#pragma once
// Wavefront OBJ: v, vn, vt and f statements; the rest of the format carries nothing a mesh needs.
#include <string>
#include <string_view>

#include "engine/geometry/triangle_mesh.h"

namespace rtrt {

// Wavefront OBJ text as a triangle mesh (LoadMesh's rules, mesh_io.h); PATH names the file in
// messages ("line 33").
TriangleMesh ParseObj(const std::string& path, std::string_view text);

}  // namespace rtrt
