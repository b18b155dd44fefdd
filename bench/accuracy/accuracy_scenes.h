#pragma once
// The scenes of `rtrt bench accuracy`, defined exactly in docs/accuracy.md.
//
// Dragon scene: the paper scene (paper_scene.h: the dragon fitted to extent 5, camera, light,
// background) plus a tilted ground of two triangles with corners 10^5 from the origin (their
// interpolated hit points err by ~10^-3 along the normal, ten times a fixed 10^-4 ray offset) and a
// glass sphere standing on it (refraction needs depth 3 to pass through it). Far spheres: 7 x 4
// instances of a sphere of radius 1.5, 4000 from a telephoto camera (0.3 degrees), where the
// textbook quadratic loses the digits of r^2.
#include <memory>
#include <string>

#include "engine/render_rt/render_scene.h"

namespace rtrt {

inline constexpr float kGroundHalfSize = 1e5f;

// blas: the dragon, fitted to extent 5 (FitMesh).
RenderScene MakeAccuracyDragonScene(std::shared_ptr<const Blas> dragon);
RenderScene MakeFarSpheresScene();

// Replaces the scene's SAH TLAS with the runtime's (DynamicTlas: an LBVH, refit between
// rebuilds) as a runtime that rebuilds it every N frames has it N frames after a rebuild: built
// where the instances stood `frames` frames ago, each having moved since at kInstanceSpeed per
// frame in its own direction in the xy plane (instance i at the angle 2.39996 i), then refit to
// where they stand now; frames 0: rebuilt this frame. Refit boxes are conservative, so the image
// is the same; only traversal time can change.
inline constexpr float kInstanceSpeed = 0.2f;
void UseRuntimeTlas(RenderScene& scene, uint32_t frames);

// The ground's height at (x, z): it rises 0.1 per unit away from the camera (-z) and 0.05
// toward +x, through (0, groundY0, 0). The tilt gives the rounding error of its hit points
// (~10^-2 per coordinate, from vertices 10^5 away) a component along the normal.
inline float GroundHeight(float groundY0, float x, float z) {
    return groundY0 + 0.05f * x - 0.1f * z;
}

}  // namespace rtrt
