#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include "bench/accuracy/accuracy_dispatch.h"
#include "bench/accuracy/accuracy_renderer.h"
#include "engine/render_rt/cpu/trace_tiles.h"

namespace rtrt {
namespace {

template <typename PixelFn>
void ForEachPixel(uint32_t width, uint32_t height, PixelFn&& pixel) {
    constexpr uint32_t kTile = 16;
    tbb::parallel_for(tbb::blocked_range2d<uint32_t>(0, height, kTile, 0, width, kTile),
                      [&](const tbb::blocked_range2d<uint32_t>& tile) {
                          for (uint32_t y = tile.rows().begin(); y != tile.rows().end(); ++y)
                              for (uint32_t x = tile.cols().begin(); x != tile.cols().end(); ++x)
                                  pixel(x, y);
                      });
}

RenderSceneView View(const RenderScene& scene, const RenderSettings& settings) {
    RenderSceneView view = scene.HostView(settings.width, settings.height, settings.maxDepth);
    view.samplesPerPixel = settings.samplesPerPixel;
    return view;
}

}  // namespace

void RenderAccuracyCpu(const RenderScene& scene, const RenderSettings& settings, uint32_t accuracy,
                       Image& image, RenderStats* stats) {
    if (image.width != settings.width || image.height != settings.height)
        image = Image(settings.width, settings.height);
    const RenderSceneView view = View(scene, settings);
    uint64_t rays = 0;
    DispatchAccuracy(accuracy, [&](auto tag) {
        using Policy = AccuracyPolicy<decltype(tag)::value>;
        rays = TraceTiles<kAccuracyFeatures, Policy>(view, ViewMode::kShaded, image);
    });
    if (stats) stats->rays = rays;
}

ObjectIds PrimaryObjectsCpu(const RenderScene& scene, const RenderSettings& settings,
                            uint32_t accuracy) {
    const RenderSceneView view = View(scene, settings);
    ObjectIds ids(size_t(settings.width) * settings.height);
    DispatchAccuracy(accuracy, [&](auto tag) {
        using Policy = AccuracyPolicy<decltype(tag)::value>;
        ForEachPixel(settings.width, settings.height, [&](uint32_t x, uint32_t y) {
            SceneHit hit;
            const Ray ray = PrimaryRay(view.camera, x, y, view.width, view.height);
            const bool found =
                TraceIntersect<kAccuracyFeatures, Policy>(view.tlas, ray, &hit, nullptr);
            ids[size_t(y) * settings.width + x] = found ? hit.instance + 1 : 0;
        });
    });
    return ids;
}

}  // namespace rtrt
