#include <cub/cub.cuh>
#include <vector>

#include "engine/bvh/build/gpu_lbvh.h"
#include "engine/bvh/tlas/tlas.h"
#include "engine/render_rt/cuda/cuda_frame_renderer.h"
#include "engine/render_rt/cuda/cuda_trace.h"
#include "engine/render_rt/cuda/device_scene.h"
#include "engine/render_rt/pixel_kernel.h"

namespace rtrt {
namespace {

constexpr int kBlock = 256;
uint32_t Blocks(size_t n) { return uint32_t((n + kBlock - 1) / kBlock); }

// Writes the changed records into place and recomputes their world boxes.
__global__ void ScatterInstancesKernel(const uint32_t* indices, const Instance* records,
                                       uint32_t count, const Aabb* blasBounds, Instance* instances,
                                       Aabb* worldBounds) {
    const uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
    if (k >= count) return;
    const Instance inst = records[k];
    instances[indices[k]] = inst;
    worldBounds[indices[k]] = TransformBounds(inst.objectToWorld, blasBounds[inst.blasId]);
}

__global__ void AllWorldBoundsKernel(const Instance* instances, uint32_t n, const Aabb* blasBounds,
                                     Aabb* worldBounds) {
    const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n) return;
    worldBounds[i] = TransformBounds(instances[i].objectToWorld, blasBounds[instances[i].blasId]);
}

// Each node's term of the SAH cost (ComputeStats on the CPU), relative to the root's area; the
// unused position 1 and an empty tree add nothing.
__global__ void SahTermsKernel(const BvhNode* nodes, uint32_t positions, float* terms) {
    const uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= positions) return;
    const float rootArea = nodes[0].Bounds().Area();
    const BvhNode node = nodes[i];
    float term = 0.0f;
    if (i != 1 && rootArea > 0.0f) {
        const float rel = node.Bounds().Area() / rootArea;
        term = node.IsLeaf() ? kSahIntersectionCost * float(node.primCount) * rel
                             : kSahTraversalCost * rel;
    }
    terms[i] = term;
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

}  // namespace

struct CudaFrameRenderer::Impl {
    TlasPolicy policy;
    DeviceScene device;
    DeviceBuffer<Aabb> blasBounds;
    DeviceBuffer<Instance> instances;
    DeviceBuffer<Aabb> worldBounds;
    DeviceBuffer<uint32_t> changedIndices;
    DeviceBuffer<Instance> changedRecords;
    std::vector<uint32_t> hostIndices;
    std::vector<Instance> hostRecords;
    GpuLbvh tlas;
    bool built = false;
    float rebuiltSahCost = 0.0f;
    float lastSahCost = 0.0f;
    DeviceBuffer<float> sahTerms, sahSum;
    float* sahHost = nullptr;  // pinned: the cost arrives without a synchronous copy
    bool sahPending = false, sahPendingIsRebuild = false;
    DeviceBuffer<unsigned char> scratch;
    DeviceBuffer<vec3> frame;
    DeviceBuffer<unsigned long long> rayCount;
    cudaEvent_t events[4];
    GpuFrameTimes times;

    explicit Impl(const RenderScene& scene, TlasPolicy p) : policy(p), device(scene) {
        std::vector<Aabb> bounds;
        for (const auto& blas : scene.blases) bounds.push_back(blas->bounds);
        blasBounds.Upload(bounds);
        for (cudaEvent_t& e : events) RT_CUDA_CHECK(cudaEventCreate(&e));
        rayCount.Resize(1);
        sahSum.Resize(1);
        RT_CUDA_CHECK(cudaMallocHost(&sahHost, sizeof(float)));
    }
    ~Impl() {
        for (cudaEvent_t e : events) cudaEventDestroy(e);
        cudaFreeHost(sahHost);
    }

    // The cost the last update queued, once its copy has landed.
    void CollectSahCost() {
        if (!sahPending) return;
        RT_CUDA_CHECK(cudaEventSynchronize(events[2]));
        lastSahCost = *sahHost;
        if (sahPendingIsRebuild) rebuiltSahCost = lastSahCost;
        sahPending = false;
    }

    // Every record again, after the instance count changed.
    void UploadAll(const RenderScene& scene) {
        const uint32_t n = uint32_t(scene.instances.size());
        instances.Upload(scene.instances);
        worldBounds.Resize(n);
        if (n == 0) return;
        AllWorldBoundsKernel<<<Blocks(n), kBlock>>>(instances.Data(), n, blasBounds.Data(),
                                                    worldBounds.Data());
        RT_CUDA_CHECK_LAUNCH();
    }

    uint32_t UploadChanged(const RenderScene& scene, std::span<const uint32_t> changed) {
        hostIndices.clear();
        hostRecords.clear();
        for (uint32_t i : changed) {
            hostIndices.push_back(i);
            hostRecords.push_back(scene.instances[i]);
        }
        const uint32_t count = uint32_t(hostIndices.size());
        if (count == 0) return 0;
        if (changedIndices.Size() < count) {
            changedIndices.Resize(count);
            changedRecords.Resize(count);
        }
        RT_CUDA_CHECK(cudaMemcpyAsync(changedIndices.Data(), hostIndices.data(),
                                      count * sizeof(uint32_t), cudaMemcpyHostToDevice));
        RT_CUDA_CHECK(cudaMemcpyAsync(changedRecords.Data(), hostRecords.data(),
                                      count * sizeof(Instance), cudaMemcpyHostToDevice));
        ScatterInstancesKernel<<<Blocks(count), kBlock>>>(
            changedIndices.Data(), changedRecords.Data(), count, blasBounds.Data(),
            instances.Data(), worldBounds.Data());
        RT_CUDA_CHECK_LAUNCH();
        return count;
    }

    // Queues the SAH cost of the tree; it arrives in sahHost.
    void QueueSahCost(bool afterRebuild) {
        const uint32_t n = tlas.Count();
        const uint32_t positions = n == 0 ? 2u : 2u * n;
        if (sahTerms.Size() < positions) sahTerms.Resize(positions);
        SahTermsKernel<<<Blocks(positions), kBlock>>>(tlas.Nodes(), positions, sahTerms.Data());
        RT_CUDA_CHECK_LAUNCH();
        size_t bytes = 0;
        RT_CUDA_CHECK(
            cub::DeviceReduce::Sum(nullptr, bytes, sahTerms.Data(), sahSum.Data(), int(positions)));
        if (scratch.Size() < bytes) scratch.Resize(bytes);
        // CUB's reduction is deterministic run to run, so the rebuild decisions are too.
        RT_CUDA_CHECK(cub::DeviceReduce::Sum(scratch.Data(), bytes, sahTerms.Data(), sahSum.Data(),
                                             int(positions)));
        RT_CUDA_CHECK(
            cudaMemcpyAsync(sahHost, sahSum.Data(), sizeof(float), cudaMemcpyDeviceToHost));
        sahPending = true;
        sahPendingIsRebuild = afterRebuild;
    }
};

CudaFrameRenderer::CudaFrameRenderer(const RenderScene& scene, TlasPolicy policy) {
    std::string why;
    if (!CudaBackendAvailable(&why)) throw std::runtime_error(why + "; use --backend cpu");
    impl_ = std::make_unique<Impl>(scene, policy);
    impl_->UploadAll(scene);
    std::vector<uint32_t> none;
    Update(scene, none);
}

CudaFrameRenderer::~CudaFrameRenderer() = default;

void CudaFrameRenderer::Update(const RenderScene& scene, std::span<const uint32_t> changed) {
    Impl& m = *impl_;
    m.CollectSahCost();
    m.times = {};
    RT_CUDA_CHECK(cudaEventRecord(m.events[0]));
    const uint32_t n = uint32_t(scene.instances.size());
    const bool countChanged = m.instances.Size() != n;
    if (countChanged) {
        m.UploadAll(scene);
        m.times.uploaded = n;
    } else {
        m.times.uploaded = m.UploadChanged(scene, changed);
    }
    RT_CUDA_CHECK(cudaEventRecord(m.events[1]));
    // The policy of DynamicTlas, with one difference: a tree's SAH cost is known one update
    // later (it is copied back asynchronously), so that no frame waits on the GPU halfway.
    const bool rebuild = m.policy.alwaysRebuild || countChanged || !m.built ||
                         m.lastSahCost > (1.0f + m.policy.maxSahGrowth) * m.rebuiltSahCost;
    if (rebuild) {
        m.tlas.Build(m.worldBounds.Data(), n);
        m.built = true;
    } else if (m.times.uploaded > 0) {
        m.tlas.Refit(m.worldBounds.Data());
    }
    // Always-rebuild (the benchmark's mode) needs no cost.
    if ((rebuild || m.times.uploaded > 0) && !m.policy.alwaysRebuild) m.QueueSahCost(rebuild);
    RT_CUDA_CHECK(cudaEventRecord(m.events[2]));
    m.times.tlasRebuilt = rebuild;
    m.times.tlasSahCost = m.lastSahCost;
}

void CudaFrameRenderer::Trace(const RenderScene& scene, const RenderSettings& settings,
                              Image* image, RenderStats* stats) {
    Impl& m = *impl_;
    RenderSceneView view = m.device.View(scene, settings);
    view.tlas = {m.tlas.Nodes(), m.tlas.PrimOrder(), m.instances.Data(), view.tlas.blases};
    const size_t pixels = size_t(settings.width) * settings.height;
    if (m.frame.Size() != pixels) m.frame.Resize(pixels);
    if (stats) RT_CUDA_CHECK(cudaMemsetAsync(m.rayCount.Data(), 0, sizeof(unsigned long long)));
    LaunchTrace(view, settings.view,
                EffectiveFeatures(scene.Features(), settings.enabledFeatures, settings.view),
                m.frame.Data(), stats ? m.rayCount.Data() : nullptr);
    RT_CUDA_CHECK(cudaEventRecord(m.events[3]));
    RT_CUDA_CHECK(cudaEventSynchronize(m.events[3]));
    m.times.uploadMs = Elapsed(m.events[0], m.events[1]);
    m.times.tlasMs = Elapsed(m.events[1], m.events[2]);
    m.times.traceMs = Elapsed(m.events[2], m.events[3]);
    if (image) {
        image->width = settings.width;
        image->height = settings.height;
        image->pixels.resize(pixels);
        m.frame.Download(image->pixels);
    }
    if (stats) {
        unsigned long long rays = 0;
        m.rayCount.Download(std::span<unsigned long long>(&rays, 1));
        stats->rays = rays;
    }
}

bool CudaFrameRenderer::Pick(const Ray& ray, SceneHit* hit) {
    Impl& m = *impl_;
    DeviceBuffer<SceneHit> deviceHit;
    deviceHit.Resize(1);
    DeviceBuffer<uint32_t> found;
    found.Resize(1);
    const TlasView tlas{m.tlas.Nodes(), m.tlas.PrimOrder(), m.instances.Data(),
                        m.device.blasViews.Data()};
    PickKernel<<<1, 1>>>(tlas, ray, deviceHit.Data(), found.Data());
    RT_CUDA_CHECK_LAUNCH();
    uint32_t f = 0;
    found.Download(std::span<uint32_t>(&f, 1));
    deviceHit.Download(std::span<SceneHit>(hit, 1));
    return f != 0;
}

const vec3* CudaFrameRenderer::DeviceFrame() const { return impl_->frame.Data(); }

const GpuFrameTimes& CudaFrameRenderer::Times() const { return impl_->times; }

Lbvh CudaFrameRenderer::DownloadTlas() const { return impl_->tlas.Download(); }

}  // namespace rtrt
