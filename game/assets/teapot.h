#pragma once
// The Utah teapot (Newell 1975) tessellated from its 32 bicubic Bezier patches.
#include <string>

#include "engine/geometry/triangle_mesh.h"

namespace rtrt {

inline constexpr int kMaxTeapotResolution = 256;

// Reads the patches from POV-Ray's teapot.inc (Newell's data as adapted by Alexander Enzmann, CC BY
// 3.0; Debian package povray-examples, file
// usr/share/doc/povray/examples/advanced/teapot/teapot.inc; tools/fetch_models.sh fetches it, it is
// never committed) and tessellates each on a resolution x resolution grid of quads, two triangles
// per quad. Triangles with two identical vertices (at the collapsed edges of the lid and bottom
// patches) are dropped: resolution 6 gives 2,256 triangles. Identical positions are welded into one
// vertex with an area-weighted normal. The teapot stands on y = 0 with +y up and its spout towards
// +x, in the file's units (3.15 high). Throws InputError for a missing or malformed file or a
// resolution outside [1, kMaxTeapotResolution].
TriangleMesh TessellateTeapot(const std::string& teapotIncPath, int resolution);

}  // namespace rtrt
