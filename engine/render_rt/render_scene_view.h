#pragma once
// Everything a trace kernel reads, as plain pointers into host or device memory.
#include "engine/bvh/traversal/scene_traversal.h"
#include "engine/render_rt/camera.h"
#include "engine/render_rt/scene_features.h"
#include "engine/render_rt/shading/light.h"
#include "engine/render_rt/shading/pbr_material.h"
#include "engine/render_rt/shading/texture.h"

namespace rtrt {

struct RenderSceneView {
    TlasView tlas;
    const Material* materials;
    const PbrMaterial* pbrMaterials;  // indexed by Material::pbrMaterial
    const Light* lights;
    const Texture* textures;  // indexed by the materials' texture slots
    const uint32_t* texels;   // RGBA8, the Texture records' texelOffset counts in these
    uint32_t lightCount;
    uint32_t maxDepth;  // rays per path: 1 = primary only, 2 = primary plus one bounce
    CameraFrame camera;
    vec3 background;
    uint32_t width, height;
    uint32_t samplesPerPixel;  // shaded view: n x n stratified samples (pixel_sample.h)
};

// The largest maxDepth the per-pixel ray stack holds (each bounce adds at most one entry).
inline constexpr uint32_t kMaxRayDepth = 16;

}  // namespace rtrt
