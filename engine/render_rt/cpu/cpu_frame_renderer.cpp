#include "engine/render_rt/cpu/cpu_frame_renderer.h"

#include <vector>

#include "engine/bvh/tlas/tlas.h"
#include "engine/core/timer.h"
#include "engine/render_rt/cpu/cpu_deformer.h"
#include "engine/render_rt/cpu/cpu_trace.h"

namespace rtrt {
namespace {

class CpuFrameRenderer final : public FrameRenderer {
  public:
    CpuFrameRenderer(const RenderScene& scene, TlasPolicy policy, BlasRebuildPolicy blasPolicy)
        : tlas_(policy), deformer_(blasPolicy) {
        Update(scene, {{}, true});
    }

    Backend Kind() const override { return Backend::kCpu; }

    void Update(const RenderScene& scene, const SceneChanges& changes) override {
        pending_ = {};
        pending_.tlasSahCost = lastSahCost_;
        instances_ = scene.instances.data();
        const size_t known = blasViews_.size();
        for (size_t id = known; id < scene.blases.size(); ++id) {
            blasViews_.push_back(scene.blases[id]->View());
            blasBounds_.push_back(scene.blases[id]->bounds);
        }
        for (const BlasOutline& outline : scene.BlasOutlines(known))
            blasOutlines_.push_back(outline);
        const DeformStats deformed =
            deformer_.Update(scene, changes.deformations, blasViews_, blasBounds_);
        pending_.deformMs = deformed.deformMs;
        pending_.blasMs = deformed.blasMs;
        pending_.deformed = deformed.deformed;
        pending_.blasRebuilt = deformed.rebuilt;
        // A record count the tree does not cover is a topology change, reported or not.
        const bool topology = changes.topologyChanged || !built_ ||
                              tlas_.Tree().primOrder.size() != scene.instances.size();
        if (changes.instances.empty() && !topology && deformed.deformed == 0) return;
        Stopwatch timer;
        const TlasUpdateStats s =
            tlas_.Update(scene.instances, blasBounds_, topology, blasOutlines_);
        built_ = true;
        pending_.tlasMs = timer.Milliseconds();
        pending_.tlasRebuilt = s.rebuilt;
        pending_.tlasSahCost = lastSahCost_ = s.sahCost;
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
        // A frame traced again without an update spent nothing on the TLAS.
        pending_ = {};
        pending_.tlasSahCost = lastSahCost_;
    }

    void Finish() override {}

    bool Pick(const Ray& ray, SceneHit* hit) override {
        if (!instances_) return false;
        return IntersectScene(TlasViewOf(), ray, hit);
    }

    const FrameTimes& Times() const override { return times_; }
    const vec3* DeviceFrame() const override { return nullptr; }
    Tlas CurrentTlas() const override { return {tlas_.Tree().nodes}; }

  private:
    TlasView TlasViewOf() const {
        return {tlas_.Tree().nodes.data(), instances_, blasViews_.data()};
    }

    RenderSceneView View(const RenderScene& scene, const RenderSettings& settings) const {
        RenderSceneView view = scene.HostView(settings.width, settings.height, settings.maxDepth);
        view.tlas = TlasViewOf();
        return view;
    }

    DynamicTlas tlas_;
    CpuDeformer deformer_;
    bool built_ = false;
    std::vector<BlasView> blasViews_;
    std::vector<Aabb> blasBounds_;
    std::vector<BlasOutline> blasOutlines_;
    // The scene's records as of the last update or trace: Pick reads them, so the scene must
    // not have changed size since (a frame loop picks before it advances).
    const Instance* instances_ = nullptr;
    float lastSahCost_ = 0.0f;
    Image frame_;  // where frames nobody asked to see go
    uint64_t traced_ = 0;
    FrameTimes pending_, times_;
};

}  // namespace

std::unique_ptr<FrameRenderer> MakeCpuFrameRenderer(const RenderScene& scene, TlasPolicy policy,
                                                    BlasRebuildPolicy blasPolicy) {
    return std::make_unique<CpuFrameRenderer>(scene, policy, blasPolicy);
}

}  // namespace rtrt
