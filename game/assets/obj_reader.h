#pragma once
// Wavefront OBJ: v, vn, vt and f statements; the rest of the format carries nothing a mesh needs.
#include <cstdint>
#include <string>
#include <string_view>

#include "engine/geometry/triangle_mesh.h"

namespace rtrt {

// Wavefront OBJ text as a triangle mesh (LoadMesh's rules, mesh_io.h); PATH names the file in
// messages ("line 33"). fileVertices, where given, receives the number of `v` statements (the
// mesh has more vertices where corners of one give it different normals).
TriangleMesh ParseObj(const std::string& path, std::string_view text,
                      uint64_t* fileVertices = nullptr);

}  // namespace rtrt
