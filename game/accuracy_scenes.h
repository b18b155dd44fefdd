#pragma once
// The scenes of `rtrt bench accuracy`, defined exactly in docs/accuracy.md.
//
// Dragon scene: the paper scene (paper_scene.h: the dragon fitted to extent 5, camera, light,
// background) plus a tilted ground of two triangles with corners 10^4 from the origin (their
// interpolated hit points err by ~10^-3, ten times a fixed 10^-4 ray offset) and a glass sphere
// standing on it (refraction needs depth 3 to pass through it).
// Far spheres: 7 x 4 spheres of radius 1.5, 4000 from a telephoto camera (0.3 degrees), where
// the textbook quadratic loses the digits of r^2.
#include <memory>
#include <string>

#include "engine/render_rt/render_scene.h"

namespace rtrt {

inline constexpr float kGroundHalfSize = 1e4f;

// blas: the dragon, fitted to extent 5 (FitMesh).
RenderScene MakeAccuracyDragonScene(std::shared_ptr<const Blas> dragon);
RenderScene MakeFarSpheresScene();

// The ground's height at (x, z): it rises 0.02 per unit toward +z and 0.01 toward +x, through
// (0, groundY0, 0).
inline float GroundHeight(float groundY0, float x, float z) {
    return groundY0 + 0.01f * x + 0.02f * z;
}

}  // namespace rtrt
