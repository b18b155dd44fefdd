#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <atomic>

#include "engine/render_rt/cpu/cpu_trace.h"
#include "engine/render_rt/pixel_kernel.h"
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
    constexpr uint32_t kTile = 16;
    std::atomic<uint64_t> rays{0};
    DispatchFeatures(features, [&](auto featureTag) {
        constexpr uint32_t kFeatures = decltype(featureTag)::value;
        tbb::parallel_for(
            tbb::blocked_range2d<uint32_t>(0, settings.height, kTile, 0, settings.width, kTile),
            [&](const tbb::blocked_range2d<uint32_t>& tile) {
                uint32_t tileRays = 0;
                for (uint32_t y = tile.rows().begin(); y != tile.rows().end(); ++y)
                    for (uint32_t x = tile.cols().begin(); x != tile.cols().end(); ++x)
                        image.At(x, y) = RawPixel<kFeatures>(view, settings.view, x, y, &tileRays);
                rays += tileRays;
            });
    });
    if (stats) stats->rays = rays.load();
}

void RenderInto(const RenderScene& scene, const RenderSettings& settings, Image& image,
                RenderStats* stats) {
    TraceViewCpu(scene.HostView(settings.width, settings.height, settings.maxDepth),
                 scene.Features(), settings, image, stats);
}

}  // namespace rtrt
