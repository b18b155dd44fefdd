#include "engine/render_rt/cpu/cpu_frame_renderer.h"

#include <vector>

#include "engine/core/timer.h"
#include "engine/render_rt/cpu/cpu_trace.h"

namespace rtrt {
namespace {

class CpuFrameRenderer final : public FrameRenderer {
  public:
    CpuFrameRenderer(const RenderScene& scene, TlasPolicy policy) : tlas_(policy) {
        Update(scene, {{}, true});
    }

    Backend Kind() const override { return Backend::kCpu; }

    void Update(const RenderScene& scene, const SceneChanges& changes) override {
        pending_ = {};
        TakeBlases(scene);
        instances_ = scene.instances.data();
        if (changes.instances.empty() && !changes.topologyChanged && built_) return;
        Stopwatch timer;
        const TlasUpdateStats s =
            tlas_.Update(scene.instances, blasBounds_, changes.topologyChanged || !built_);
        built_ = true;
        pending_.tlasMs = timer.Milliseconds();
        pending_.tlasRebuilt = s.rebuilt;
        pending_.tlasSahCost = s.sahCost;
    }

    void Trace(const RenderScene& scene, const RenderSettings& settings, Image* image,
               RenderStats* stats) override {
        instances_ = scene.instances.data();
        Stopwatch timer;
        RenderStats counted;
        TraceViewCpu(View(scene, settings), scene.Features(), settings, image ? *image : frame_,
                     stats ? &counted : nullptr);
        pending_.traceMs = timer.Milliseconds();
        pending_.rays = counted.rays;
        if (stats) *stats = counted;
        pending_.frame = ++traced_;
        times_ = pending_;
    }

    void Finish() override {}

    bool Pick(const Ray& ray, SceneHit* hit) override {
        if (!instances_) return false;
        return IntersectScene(Tlas(), ray, hit);
    }

    const FrameTimes& Times() const override { return times_; }
    const vec3* DeviceFrame() const override { return nullptr; }
    Lbvh CurrentTlas() const override { return tlas_.Tree(); }

  private:
    // Models added to the scene since the last update (the window's spawn palette adds some).
    void TakeBlases(const RenderScene& scene) {
        for (size_t i = blasViews_.size(); i < scene.blases.size(); ++i) {
            blasViews_.push_back(scene.blases[i]->View());
            blasBounds_.push_back(scene.blases[i]->bounds);
        }
    }

    TlasView Tlas() const {
        return {tlas_.Tree().nodes.data(), tlas_.Tree().primOrder.data(), instances_,
                blasViews_.data()};
    }

    RenderSceneView View(const RenderScene& scene, const RenderSettings& settings) const {
        RenderSceneView view = scene.HostView(settings.width, settings.height, settings.maxDepth);
        view.tlas = Tlas();
        return view;
    }

    DynamicTlas tlas_;
    bool built_ = false;
    std::vector<BlasView> blasViews_;
    std::vector<Aabb> blasBounds_;
    const Instance* instances_ = nullptr;  // the scene's records as of the last update
    Image frame_;                          // where frames nobody asked to see go
    uint64_t traced_ = 0;
    FrameTimes pending_, times_;
};

}  // namespace

std::unique_ptr<FrameRenderer> MakeCpuFrameRenderer(const RenderScene& scene, TlasPolicy policy) {
    return std::make_unique<CpuFrameRenderer>(scene, policy);
}

}  // namespace rtrt
