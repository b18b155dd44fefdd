#include <tbb/parallel_for.h>

#include "bench/accuracy/accuracy_renderer.h"
#include "bench/accuracy/reference_trace.h"

namespace rtrt {

Image RenderReference(const RenderScene& scene, const RenderSettings& settings) {
    RenderSceneView view = scene.HostView(settings.width, settings.height, settings.maxDepth);
    view.samplesPerPixel = settings.samplesPerPixel;
    const reference::CameraFrameD camera =
        reference::MakeCameraFrameD(scene.camera, settings.width, settings.height);
    Image image(settings.width, settings.height);
    tbb::parallel_for(0u, settings.height, [&](uint32_t y) {
        for (uint32_t x = 0; x < settings.width; ++x)
            image.At(x, y) = vec3(reference::ReferencePixel(view, camera, x, y));
    });
    return image;
}

ObjectIds ReferencePrimaryObjects(const RenderScene& scene, const RenderSettings& settings) {
    const RenderSceneView view = scene.HostView(settings.width, settings.height, 1);
    const reference::CameraFrameD camera =
        reference::MakeCameraFrameD(scene.camera, settings.width, settings.height);
    ObjectIds ids(size_t(settings.width) * settings.height);
    tbb::parallel_for(0u, settings.height, [&](uint32_t y) {
        for (uint32_t x = 0; x < settings.width; ++x) {
            reference::HitD hit;
            const reference::RayD ray =
                reference::PrimaryRayD(camera, x + 0.5, y + 0.5, settings.width, settings.height);
            const bool found = reference::TraceSceneD<Query::kIntersect>(view.tlas, ray, &hit);
            ids[size_t(y) * settings.width + x] = found ? hit.instance + 1 : 0;
        }
    });
    return ids;
}

}  // namespace rtrt
