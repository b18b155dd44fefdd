#pragma once
// Shapes rtrt makes itself: an axis-aligned box and a square plane as triangle meshes (flat
// normals), and a sphere as a one-primitive sphere BLAS.
#include "engine/bvh/blas/blas.h"
#include "engine/geometry/triangle_mesh.h"

namespace rtrt {

TriangleMesh MakeBoxMesh(vec3 size);                   // centred on the origin
TriangleMesh MakePlaneMesh(float sizeX, float sizeZ);  // in y = 0, normal +y, centred

// Scales and moves a mesh in place so its largest extent is `extent` and its bounding box is
// centred on the origin (the paper scene's normalisation).
void FitMesh(TriangleMesh& mesh, float extent);

// FitMesh done to a mesh's built BLAS: sourceBounds is the box of the vertices its triangles use
// (RtModelInfo::sourceBounds), so the vertices land exactly where FitMesh puts them.
void FitBlas(Blas& blas, const Aabb& sourceBounds, float extent);

}  // namespace rtrt
