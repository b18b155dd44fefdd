#include <array>
#include <optional>
#include <vector>

#include "engine/bvh/tlas/gpu_tlas.h"
#include "engine/bvh/tlas/tlas.h"
#include "engine/core/cuda_device_guard.h"
#include "engine/render_rt/cuda/cuda_deformer.h"
#include "engine/render_rt/cuda/cuda_frame_renderer.h"
#include "engine/render_rt/cuda/cuda_trace.h"
#include "engine/render_rt/cuda/device_scene.h"
#include "engine/render_rt/cuda/gpu_band_renderer.h"
#include "engine/render_rt/cuda/multi_gpu_frame_renderer.h"
#include "engine/render_rt/cuda/tlas_sah_cost.h"
#include "engine/render_rt/pixel_kernel.h"

namespace rtrt {
namespace {

constexpr int kBlock = 256;
constexpr uint32_t kMaxTraceBands = 64;
uint32_t Blocks(size_t n) { return uint32_t((n + kBlock - 1) / kBlock); }

// Writes the changed records into place (the TLAS computes their world boxes as it reads them),
// leaving the TLAS's words in them for its refit.
__global__ void ScatterInstancesKernel(const uint32_t* indices, const Instance* records,
                                       uint32_t count, Instance* instances) {
    const uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
    if (k >= count) return;
    SetPlacement(instances[indices[k]], records[k]);
}

__global__ void PickKernel(TlasView tlas, Ray ray, SceneHit* hit, uint32_t* found) {
    SceneHit h{};
    *found = IntersectScene(tlas, ray, &h) ? 1u : 0u;
    *hit = h;
}

double Elapsed(cudaEvent_t a, cudaEvent_t b) {
    float ms = 0.0f;
    RT_CUDA_CHECK(cudaEventElapsedTime(&ms, a, b));
    return ms;
}

// The events of one frame: start, the deformer's four (deform_events), instances uploaded, TLAS
// done, traced. Two sets take turns,
// so a frame's times are read when the set comes round again (or by Finish), never by waiting
// for the frame that was just queued.
struct FrameEvents {
    cudaEvent_t events[8];
    // A split frame (RenderSettings::traceBands > 1): the trace's start on the main stream, and
    // each band's start and end on its own stream; the bands' rows.
    cudaEvent_t traceReady = nullptr;
    std::vector<cudaEvent_t> bandStart, bandEnd;
    std::vector<RowBand> bands;
    TraversalChooser::Ticket traversal;      // the form the trace took, for the chooser
    bool pending = false;                    // recorded and not read yet
    bool counted = false;                    // rays were counted into raysHost
    unsigned long long* raysHost = nullptr;  // pinned
    FrameTimes times;                        // filled in as far as the host knows it
};

// Made, and destroyed, with its device current (MakeGpuBandRenderer; the multi-GPU renderer);
// every call makes it current.
class CudaFrameRenderer final : public GpuBandRenderer {
  public:
    CudaFrameRenderer(int device, const RenderScene& scene, TlasPolicy policy,
                      BlasRebuildPolicy blasPolicy)
        : gpu_(device), policy_(policy), device_(scene), deformer_(blasPolicy) {
        std::vector<Aabb> bounds;
        for (const auto& blas : scene.blases) bounds.push_back(blas->bounds);
        blasBounds_.Upload(bounds);
        blasOutlines_.Upload(scene.BlasOutlines());
        for (FrameEvents& f : frames_) {
            for (cudaEvent_t& e : f.events) RT_CUDA_CHECK(cudaEventCreate(&e));
            RT_CUDA_CHECK(cudaMallocHost(&f.raysHost, sizeof(unsigned long long)));
        }
        rayCount_.Resize(1);
        Update(scene, {{}, true});
    }
    ~CudaFrameRenderer() override {
        CudaDeviceGuard guard(gpu_);
        for (FrameEvents& f : frames_) {
            for (cudaEvent_t e : f.events) cudaEventDestroy(e);
            for (cudaEvent_t e : f.bandStart) cudaEventDestroy(e);
            for (cudaEvent_t e : f.bandEnd) cudaEventDestroy(e);
            if (f.traceReady) cudaEventDestroy(f.traceReady);
            cudaFreeHost(f.raysHost);
        }
        for (cudaStream_t s : bandStreams_) cudaStreamDestroy(s);
    }

    Backend Kind() const override { return Backend::kCuda; }
    int Device() const override { return gpu_; }

    void Update(const RenderScene& scene, const SceneChanges& changes) override {
        CudaDeviceGuard guard(gpu_);
        sahCost_.Collect();
        FrameEvents& f = BeginFrame();
        AddBlases(scene);
        if (deformer_.Update(scene, changes.deformations, blasBounds_.Data(),
                             {f.events[1], f.events[2], f.events[3], f.events[4]})) {
            const std::vector<BlasView> views = deformer_.Views();
            for (uint32_t d = 0; d < views.size(); ++d)
                device_.SetView(deformer_.Plan().Slot(d).blasId, views[d]);
            device_.CommitViews();
        }
        f.times.deformed = deformer_.Deformed();
        f.times.blasRebuilt = deformer_.Rebuilt();
        const uint32_t n = uint32_t(scene.instances.size());
        if (tlasSource_) return CopyTlas(f, n);
        // Added or removed instances move records around: all of them go up again.
        const bool countChanged = changes.topologyChanged || instances_.Size() != n;
        if (countChanged) {
            UploadAll(scene);
            f.times.uploaded = n;
            MapDeformedInstances(scene);
        } else {
            f.times.uploaded = UploadChanged(scene, changes.instances);
        }
        RT_CUDA_CHECK(cudaEventRecord(f.events[5]));
        // The policy of DynamicTlas, with one difference: a tree's SAH cost is known one update
        // later (copied back asynchronously; Collect waits for the previous frame's TLAS
        // stage at most, never for its trace), so that decisions stay deterministic run to run.
        // A scene within the policy's rebuildChangedUpTo (by default any) rebuilds whenever
        // records changed; its rebuilds queue no cost, so its decision reads none (the last may
        // be from before the scene shrank).
        const bool rebuildsChanged = policy_.RebuildsChanged(n);
        const bool rebuild = policy_.alwaysRebuild || countChanged || !built_ ||
                             (rebuildsChanged ? f.times.uploaded > 0
                                              : sahCost_.Last() > (1.0f + policy_.maxSahGrowth) *
                                                                      sahCost_.Rebuilt());
        if (rebuild) {
            tlas_.Build(instances_.Data(), {blasBounds_.Data(), blasOutlines_.Data()}, n);
            built_ = true;
        } else if (f.times.uploaded > 0) {
            tlas_.Refit(instances_.Data(), {blasBounds_.Data(), blasOutlines_.Data()});
        }
        // Always-rebuild (the benchmark's mode) and rebuilds whenever records changed need no cost.
        if ((rebuild || f.times.uploaded > 0) && !policy_.alwaysRebuild && !rebuildsChanged)
            sahCost_.Queue(tlas_.Nodes(), tlas_.Count(), rebuild);
        RT_CUDA_CHECK(cudaEventRecord(f.events[6]));
        f.times.tlasRebuilt = rebuild;
        f.times.tlasSahCost = sahCost_.Last();
    }

    void Trace(const RenderScene& scene, const RenderSettings& settings, Image* image,
               RenderStats* stats) override {
        CudaDeviceGuard guard(gpu_);
        FrameEvents& f = Launch(scene, settings, stats != nullptr, std::nullopt);
        const size_t pixels = size_t(settings.width) * settings.height;
        if (image) {
            image->width = settings.width;
            image->height = settings.height;
            image->pixels.resize(pixels);
            frame_.Download(image->pixels);  // waits for the frame: its times are known too
            Collect(f);
            if (stats) stats->rays = f.times.rays;
        }
        CollectOtherIfDone();
    }

    void TraceBand(const RenderScene& scene, const RenderSettings& settings, RowBand band,
                   bool countRays) override {
        CudaDeviceGuard guard(gpu_);
        Launch(scene, settings, countRays, band);
        CollectOtherIfDone();
    }

    vec3* Framebuffer() override { return frame_.Data(); }

    void CopyTlasFrom(GpuBandRenderer* source) override {
        if (tlasSource_ && !source) {  // the next Update uploads every record and builds again
            CudaDeviceGuard guard(gpu_);
            instances_.Resize(0);
            built_ = false;
        }
        tlasSource_ = source;
    }

    bool TimesOf(uint64_t frame, FrameTimes* times) override {
        CudaDeviceGuard guard(gpu_);
        for (FrameEvents& f : frames_)
            if (f.pending && f.times.frame == frame) Collect(f);
        const FrameTimes& t = history_[frame % history_.size()];
        if (frame == 0 || t.frame != frame) return false;
        *times = t;
        return true;
    }
    cudaEvent_t TlasDone() const override { return frames_[current_].events[6]; }
    const Instance* InstanceRecords() const override { return instances_.Data(); }
    const BvhNode* TlasNodes(uint32_t* nodeCount) const override {
        *nodeCount = tlas_.NodeCount();
        return tlas_.Nodes();
    }

    void Finish() override {
        CudaDeviceGuard guard(gpu_);
        // Oldest first, so that the last traced frame's times are the ones kept.
        FrameEvents& other = frames_[1 - current_];
        if (other.pending) Collect(other);
        if (frames_[current_].pending) Collect(frames_[current_]);
    }

    bool Pick(const Ray& ray, SceneHit* hit) override {
        CudaDeviceGuard guard(gpu_);
        DeviceBuffer<SceneHit> deviceHit;
        deviceHit.Resize(1);
        DeviceBuffer<uint32_t> found;
        found.Resize(1);
        PickKernel<<<1, 1>>>(TlasOnDevice(), ray, deviceHit.Data(), found.Data());
        RT_CUDA_CHECK_LAUNCH();
        uint32_t f = 0;
        found.Download(std::span<uint32_t>(&f, 1));
        deviceHit.Download(std::span<SceneHit>(hit, 1));
        return f != 0;
    }

    const FrameTimes& Times() const override { return times_; }
    const vec3* DeviceFrame() const override { return frame_.Data(); }
    Tlas CurrentTlas() const override {
        CudaDeviceGuard guard(gpu_);
        return tlas_.Download();
    }

  private:
    // Queues a frame's trace (all rows, or one band on the main stream) after the frame's update,
    // and its end event.
    FrameEvents& Launch(const RenderScene& scene, const RenderSettings& settings, bool countRays,
                        std::optional<RowBand> band) {
        FrameEvents& f = inFrame_ ? frames_[current_] : BeginEmptyFrame();
        inFrame_ = false;
        RenderSceneView view = device_.View(scene, settings);
        view.tlas = TlasOnDevice();
        const size_t pixels = size_t(settings.width) * settings.height;
        if (frame_.Size() != pixels) frame_.Resize(pixels);
        if (countRays)
            RT_CUDA_CHECK(cudaMemsetAsync(rayCount_.Data(), 0, sizeof(unsigned long long)));
        const uint32_t features = ChooseTraversal(
            f, EffectiveFeatures(scene.Features(), settings.enabledFeatures, settings.view),
            settings, !band);
        unsigned long long* rays = countRays ? rayCount_.Data() : nullptr;
        f.bands.clear();
        if (band) {
            if (band->Rows() > 0)
                LaunchTrace(view, settings.view, features, frame_.Data(), rays, 0, *band);
        } else if (settings.traceBands > 1) {
            TraceBands(f, view, settings, features, rays);
        } else {
            LaunchTrace(view, settings.view, features, frame_.Data(), rays);
        }
        if (countRays)
            RT_CUDA_CHECK(cudaMemcpyAsync(f.raysHost, rayCount_.Data(), sizeof(unsigned long long),
                                          cudaMemcpyDeviceToHost));
        RT_CUDA_CHECK(cudaEventRecord(f.events[7]));
        f.times.frame = ++traced_;
        f.times.gpuRows[0] = band ? band->Rows() : settings.height;
        f.pending = true;
        f.counted = countRays;
        return f;
    }

    // The features the frame launches with: a scene of many instances takes the traversal form
    // the settings force, or the one the chooser gives (recorded in f for its report). A band of
    // a frame split over several GPUs is not measured: its rows and its wait for the display
    // GPU's last gather change from frame to frame, so it takes kAuto's unmeasured form.
    uint32_t ChooseTraversal(FrameEvents& f, uint32_t features, const RenderSettings& settings,
                             bool measured) {
        f.traversal = {};
        if (settings.traversal != TraversalForm::kAuto || !measured) {
            features = WithTraversalForm(features, settings.traversal);
        } else if ((features & kFeatureManyInstances) != 0) {
            // What the trace time depends on besides the scene's motion.
            uint64_t configuration = features;
            for (uint64_t v : {uint64_t(settings.view), uint64_t(settings.width),
                               uint64_t(settings.height), uint64_t(settings.maxDepth),
                               uint64_t(settings.samplesPerPixel), uint64_t(settings.traceBands)})
                configuration = configuration * 0x100000001b3ull ^ v;
            f.traversal = traversal_.Next(configuration);
            features =
                WithTraversalForm(features, f.traversal.singleLoop ? TraversalForm::kSingleLoop
                                                                   : TraversalForm::kNested);
        }
        f.times.singleLoop = (features & kFeatureManyInstances) != 0;
        return features;
    }

    // The other set's frame has most likely finished by now; if so its times are shown.
    void CollectOtherIfDone() {
        FrameEvents& other = frames_[1 - current_];
        if (other.pending && cudaEventQuery(other.events[7]) == cudaSuccess) Collect(other);
    }

    // The TLAS stage when another GPU builds the tree: its records and nodes are copied here once
    // that GPU's TLAS stage is done (peer to peer where the GPUs allow it; the CUDA runtime stages
    // the copy through host memory where they do not).
    void CopyTlas(FrameEvents& f, uint32_t n) {
        RT_CUDA_CHECK(cudaEventRecord(f.events[5]));
        RT_CUDA_CHECK(cudaStreamWaitEvent(0, tlasSource_->TlasDone()));
        if (instances_.Size() != n) instances_.Resize(n);
        if (n > 0)
            RT_CUDA_CHECK(cudaMemcpyPeerAsync(instances_.Data(), gpu_,
                                              tlasSource_->InstanceRecords(), tlasSource_->Device(),
                                              n * sizeof(Instance)));
        uint32_t nodes = 0;
        const BvhNode* source = tlasSource_->TlasNodes(&nodes);
        tlas_.CopyFrom(source, tlasSource_->Device(), nodes, n);
        RT_CUDA_CHECK(cudaEventRecord(f.events[6]));
        f.times.uploaded = n;
        built_ = true;
    }

    TlasView TlasOnDevice() const {
        return {tlas_.Nodes(), instances_.Data(), device_.blasViews.Data()};
    }

    // Takes the next set of events for a frame (reading its previous frame's times first: that
    // frame was queued two frames ago) and records its start.
    FrameEvents& BeginFrame() {
        current_ = 1 - current_;
        FrameEvents& f = frames_[current_];
        if (f.pending) Collect(f);
        f.times = {};
        inFrame_ = true;
        RT_CUDA_CHECK(cudaEventRecord(f.events[0]));
        return f;
    }

    // A frame traced without an update: its upload and TLAS stages take no time.
    FrameEvents& BeginEmptyFrame() {
        FrameEvents& f = BeginFrame();
        for (int e = 1; e < 7; ++e) RT_CUDA_CHECK(cudaEventRecord(f.events[e]));
        f.times.tlasSahCost = sahCost_.Last();
        return f;
    }

    // Reads a recorded frame's stage times (waiting for it if it has not finished).
    void Collect(FrameEvents& f) {
        RT_CUDA_CHECK(cudaEventSynchronize(f.events[7]));
        const cudaEvent_t* e = f.events;
        // Start, vertices, rebuilt, gathered, refit: a rebuild sits between the two halves of
        // the deformation.
        if (f.times.deformed > 0) {
            f.times.deformMs = Elapsed(e[0], e[1]) + Elapsed(e[2], e[3]);
            f.times.blasMs = Elapsed(e[1], e[2]) + Elapsed(e[3], e[4]);
            f.times.uploadMs = Elapsed(e[4], e[5]);
        } else {  // nothing deformed: those stages cost nothing, whatever the events' resolution
            f.times.uploadMs = Elapsed(e[0], e[5]);
        }
        f.times.tlasMs = Elapsed(e[5], e[6]);
        f.times.traceMs = Elapsed(e[6], e[7]);
        f.times.gpuTraceMs[0] = f.times.traceMs;
        traversal_.Report(f.traversal, f.times.traceMs);
        f.times.rays = f.counted ? *f.raysHost : 0;
        if (!f.bands.empty() && split_ && split_->Parts() == f.bands.size()) {
            std::vector<double> ms(f.bands.size());
            for (size_t b = 0; b < f.bands.size(); ++b)
                ms[b] = Elapsed(f.bandStart[b], f.bandEnd[b]);
            split_->Report(f.bands, ms);
        }
        f.pending = false;
        history_[f.times.frame % history_.size()] = f.times;
        if (f.times.frame > times_.frame) times_ = f.times;
    }

    // The frame in row bands, each on its own stream once the main stream has the scene ready;
    // the main stream goes on when every band is done. The shares follow the bands' times as
    // their frames are collected.
    void TraceBands(FrameEvents& f, const RenderSceneView& view, const RenderSettings& settings,
                    uint32_t features, unsigned long long* rays) {
        const uint32_t parts = std::min(settings.traceBands, kMaxTraceBands);
        if (!split_ || split_->Parts() != parts) split_.emplace(parts);
        while (bandStreams_.size() < parts) {
            cudaStream_t s;
            RT_CUDA_CHECK(cudaStreamCreateWithFlags(&s, cudaStreamNonBlocking));
            bandStreams_.push_back(s);
        }
        if (!f.traceReady) RT_CUDA_CHECK(cudaEventCreate(&f.traceReady));
        while (f.bandStart.size() < parts) {
            f.bandStart.emplace_back();
            f.bandEnd.emplace_back();
            RT_CUDA_CHECK(cudaEventCreate(&f.bandStart.back()));
            RT_CUDA_CHECK(cudaEventCreate(&f.bandEnd.back()));
        }
        f.bands = split_->Bands(settings.height);
        RT_CUDA_CHECK(cudaEventRecord(f.traceReady));
        for (uint32_t b = 0; b < parts; ++b) {
            cudaStream_t s = bandStreams_[b];
            RT_CUDA_CHECK(cudaStreamWaitEvent(s, f.traceReady));
            RT_CUDA_CHECK(cudaEventRecord(f.bandStart[b], s));
            LaunchTrace(view, settings.view, features, frame_.Data(), rays, s, f.bands[b]);
            RT_CUDA_CHECK(cudaEventRecord(f.bandEnd[b], s));
            RT_CUDA_CHECK(cudaStreamWaitEvent(0, f.bandEnd[b]));
        }
    }

    // Every record again, after the instance count changed.
    void UploadAll(const RenderScene& scene) { instances_.Upload(scene.instances); }

    // BLASes the scene gained (spawned models, new deformations' slots), and room for their
    // boxes.
    void AddBlases(const RenderScene& scene) {
        const size_t known = blasBounds_.Size();
        if (!device_.AddBlases(scene)) return;
        blasBounds_.GrowTo(scene.blases.size());
        blasOutlines_.GrowTo(scene.blases.size());
        std::vector<Aabb> bounds;
        for (size_t id = known; id < scene.blases.size(); ++id)
            bounds.push_back(scene.blases[id]->bounds);
        const std::vector<BlasOutline> outlines = scene.BlasOutlines(known);
        RT_CUDA_CHECK(cudaMemcpy(blasBounds_.Data() + known, bounds.data(),
                                 bounds.size() * sizeof(Aabb), cudaMemcpyHostToDevice));
        RT_CUDA_CHECK(cudaMemcpy(blasOutlines_.Data() + known, outlines.data(),
                                 outlines.size() * sizeof(BlasOutline), cudaMemcpyHostToDevice));
    }

    // Which instances show each deformed BLAS: their world boxes follow the deformation.
    void MapDeformedInstances(const RenderScene& scene) {
        deformedInstances_.assign(scene.blases.size(), {});
        std::vector<uint8_t> deformed(scene.blases.size(), 0);
        for (const Deformation& d : scene.deformations)
            if (d.blasId < deformed.size()) deformed[d.blasId] = 1;
        for (uint32_t i = 0; i < scene.instances.size(); ++i)
            if (deformed[scene.instances[i].blasId])
                deformedInstances_[scene.instances[i].blasId].push_back(i);
    }

    uint32_t UploadChanged(const RenderScene& scene, std::span<const uint32_t> changed) {
        hostIndices_.clear();
        hostRecords_.clear();
        auto add = [&](uint32_t i) {
            if (i >= marks_.size()) marks_.resize(scene.instances.size(), 0);
            if (marks_[i] == mark_) return;
            marks_[i] = mark_;
            hostIndices_.push_back(i);
            hostRecords_.push_back(scene.instances[i]);
        };
        ++mark_;
        for (uint32_t i : changed) add(i);
        for (uint32_t d : deformer_.Plan().JobDeformations()) {
            const uint32_t blas = deformer_.Plan().Slot(d).blasId;
            if (blas < deformedInstances_.size())
                for (uint32_t i : deformedInstances_[blas]) add(i);
        }
        const uint32_t count = uint32_t(hostIndices_.size());
        if (count == 0) return 0;
        if (changedIndices_.Size() < count) {
            changedIndices_.Resize(count);
            changedRecords_.Resize(count);
        }
        RT_CUDA_CHECK(cudaMemcpyAsync(changedIndices_.Data(), hostIndices_.data(),
                                      count * sizeof(uint32_t), cudaMemcpyHostToDevice));
        RT_CUDA_CHECK(cudaMemcpyAsync(changedRecords_.Data(), hostRecords_.data(),
                                      count * sizeof(Instance), cudaMemcpyHostToDevice));
        ScatterInstancesKernel<<<Blocks(count), kBlock>>>(
            changedIndices_.Data(), changedRecords_.Data(), count, instances_.Data());
        RT_CUDA_CHECK_LAUNCH();
        return count;
    }

    int gpu_;
    TlasPolicy policy_;
    DeviceScene device_;
    CudaDeformer deformer_;
    std::vector<std::vector<uint32_t>> deformedInstances_;  // by BLAS id
    std::vector<uint32_t> marks_;                           // instance -> last frame queued
    uint32_t mark_ = 0;
    DeviceBuffer<Aabb> blasBounds_;
    DeviceBuffer<BlasOutline> blasOutlines_;
    DeviceBuffer<Instance> instances_;
    DeviceBuffer<uint32_t> changedIndices_;
    DeviceBuffer<Instance> changedRecords_;
    std::vector<uint32_t> hostIndices_;
    std::vector<Instance> hostRecords_;
    GpuTlas tlas_;
    bool built_ = false;
    TlasSahCost sahCost_;
    DeviceBuffer<vec3> frame_;
    DeviceBuffer<unsigned long long> rayCount_;
    TraversalChooser traversal_;
    FrameEvents frames_[2];
    std::optional<FrameSplit> split_;        // with traceBands > 1
    std::vector<cudaStream_t> bandStreams_;  // one per band
    GpuBandRenderer* tlasSource_ = nullptr;  // where the TLAS is copied from, if not built here
    uint32_t current_ = 1;                   // the first frame takes set 0
    bool inFrame_ = false;                   // Update began the frame that Trace ends
    uint64_t traced_ = 0;
    FrameTimes times_;
    std::array<FrameTimes, 4> history_;  // the last collected frames', by frame number
};

}  // namespace

std::unique_ptr<GpuBandRenderer> MakeGpuBandRenderer(int device, const RenderScene& scene,
                                                     TlasPolicy policy,
                                                     BlasRebuildPolicy blasPolicy) {
    CudaDeviceGuard guard(device);
    return std::make_unique<CudaFrameRenderer>(device, scene, policy, blasPolicy);
}

std::unique_ptr<FrameRenderer> MakeCudaFrameRenderer(const RenderScene& scene, TlasPolicy policy,
                                                     BlasRebuildPolicy blasPolicy,
                                                     const GpuSplit& gpus) {
    std::string why;
    if (!CudaBackendAvailable(&why)) throw std::runtime_error(why + "; use the CPU back end");
    if (gpus.devices.size() > 1) return MakeMultiGpuFrameRenderer(scene, policy, blasPolicy, gpus);
    int device = 0;
    if (gpus.devices.empty()) {
        RT_CUDA_CHECK(cudaGetDevice(&device));
    } else {
        device = gpus.devices[0];
    }
    return MakeGpuBandRenderer(device, scene, policy, blasPolicy);
}

}  // namespace rtrt
