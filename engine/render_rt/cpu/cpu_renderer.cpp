#include "engine/render_rt/cpu/cpu_trace.h"
#include "engine/render_rt/cpu/trace_tiles.h"
#include "engine/render_rt/renderer.h"

namespace rtrt {

void TraceViewCpu(const RenderSceneView& sceneView, uint32_t sceneFeatures,
                  const RenderSettings& settings, Image& image, RenderStats* stats) {
    if (image.width != settings.width || image.height != settings.height)
        image = Image(settings.width, settings.height);
    RenderSceneView view = sceneView;
    view.samplesPerPixel = settings.samplesPerPixel;
    const uint32_t features =
        // The traversal form matters on the GPU only: one CPU specialisation per effect set.
        EffectiveFeatures(sceneFeatures, settings.enabledFeatures, settings.view) &
        ~kFeatureManyInstances;
    uint64_t rays = 0;
    DispatchFeatures(features, [&](auto featureTag) {
        rays = TraceTiles<decltype(featureTag)::value>(view, settings.view, image);
    });
    if (stats) stats->rays = rays;
}

void RenderInto(const RenderScene& scene, const RenderSettings& settings, Image& image,
                RenderStats* stats) {
    TraceViewCpu(scene.HostView(settings.width, settings.height, settings.maxDepth),
                 scene.Features(), settings, image, stats);
}

}  // namespace rtrt
