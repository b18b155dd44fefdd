#pragma once
// The benchmark scene of the CUDA issue, defined exactly so that other renderers can run it: the
// model scaled so its largest extent is 5 and its bounding box centred on the origin; camera at
// (0,0,10) looking down -z, up +y, vertical FOV 45 degrees; material diffuse (0.8,0.1,0.1),
// ambient 0.1 x diffuse, specular 0.5 white with exponent 32, reflectivity 0.3; one directional
// light toward normalize(1,1,1) with shadows; background (0.2,0.3,0.5); max depth 2.
#include <memory>

#include "engine/render_rt/render_scene.h"

namespace rtrt {

inline constexpr uint32_t kPaperWidth = 1920, kPaperHeight = 1080, kPaperMaxDepth = 2;

// blas must already be fitted (FitMesh(mesh, 5)).
RenderScene MakePaperScene(std::shared_ptr<const Blas> blas);

}  // namespace rtrt
