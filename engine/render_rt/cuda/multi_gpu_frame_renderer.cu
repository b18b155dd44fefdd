#include <stdexcept>
#include <string>
#include <vector>

#include "engine/core/cuda_device_guard.h"
#include "engine/core/device_buffer.h"
#include "engine/render_rt/cuda/gpu_band_renderer.h"
#include "engine/render_rt/cuda/multi_gpu_frame_renderer.h"
#include "engine/render_rt/split/frame_split.h"

namespace rtrt {
namespace {

double Elapsed(cudaEvent_t a, cudaEvent_t b) {
    float ms = 0.0f;
    RT_CUDA_CHECK(cudaEventElapsedTime(&ms, a, b));
    return ms;
}

// One frame's split: each GPU's band and its start and end (on that GPU), the trace's start and
// the gathered frame (on the display GPU). Two take turns, read when they come round again, so
// no frame waits for the one just queued.
struct SplitFrame {
    std::vector<cudaEvent_t> bandStart, bandEnd;
    cudaEvent_t traceStart = nullptr, gathered = nullptr;
    std::vector<RowBand> bands;
    uint64_t frame = 0;
    bool pending = false;
    bool counted = false;
};

class MultiGpuFrameRenderer final : public FrameRenderer {
  public:
    MultiGpuFrameRenderer(const RenderScene& scene, TlasPolicy policy, BlasRebuildPolicy blasPolicy,
                          const GpuSplit& gpus)
        : split_(uint32_t(gpus.devices.size())) {
        if (gpus.devices.size() > FrameTimes::kMaxGpus)
            throw std::runtime_error("a frame can be split over at most " +
                                     std::to_string(FrameTimes::kMaxGpus) + " GPUs");
        for (int device : gpus.devices)
            gpus_.push_back(MakeGpuBandRenderer(device, scene, policy, blasPolicy));
        EnablePeerAccess();
        copiesTlas_ = gpus.tlas == GpuSplit::Tlas::kCopyFromDisplay;
        if (copiesTlas_)
            for (size_t k = 1; k < gpus_.size(); ++k) gpus_[k]->CopyTlasFrom(gpus_[0].get());
        for (SplitFrame& f : frames_) {
            for (const auto& gpu : gpus_) {
                CudaDeviceGuard guard(gpu->Device());
                f.bandStart.emplace_back();
                f.bandEnd.emplace_back();
                RT_CUDA_CHECK(cudaEventCreate(&f.bandStart.back()));
                RT_CUDA_CHECK(cudaEventCreate(&f.bandEnd.back()));
            }
            CudaDeviceGuard guard(Display());
            RT_CUDA_CHECK(cudaEventCreate(&f.traceStart));
            RT_CUDA_CHECK(cudaEventCreate(&f.gathered));
        }
    }

    ~MultiGpuFrameRenderer() override {
        for (SplitFrame& f : frames_) {
            for (size_t k = 0; k < gpus_.size(); ++k) {
                CudaDeviceGuard guard(gpus_[k]->Device());
                cudaEventSynchronize(f.bandEnd[k]);
                cudaEventDestroy(f.bandStart[k]);
                cudaEventDestroy(f.bandEnd[k]);
            }
            CudaDeviceGuard guard(Display());
            cudaEventSynchronize(f.gathered);
            cudaEventDestroy(f.traceStart);
            cudaEventDestroy(f.gathered);
        }
        // The receivers first: they may copy from the display GPU's renderer.
        for (size_t k = gpus_.size(); k-- > 0;) {
            CudaDeviceGuard guard(gpus_[k]->Device());
            gpus_[k].reset();
        }
    }

    Backend Kind() const override { return Backend::kCuda; }

    void Update(const RenderScene& scene, const SceneChanges& changes) override {
        // The display GPU's records and nodes stay as they are until the others have copied them.
        if (copiesTlas_) {
            CudaDeviceGuard guard(Display());
            for (size_t k = 1; k < gpus_.size(); ++k)
                RT_CUDA_CHECK(cudaStreamWaitEvent(0, gpus_[k]->TlasDone()));
        }
        for (const auto& gpu : gpus_) gpu->Update(scene, changes);
    }

    void Trace(const RenderScene& scene, const RenderSettings& settings, Image* image,
               RenderStats* stats) override {
        const SplitFrame& previous = frames_[current_];
        current_ = 1 - current_;
        SplitFrame& f = frames_[current_];
        if (f.pending) Collect(f);
        f.bands = split_.Bands(settings.height);
        {
            CudaDeviceGuard guard(Display());
            RT_CUDA_CHECK(cudaEventRecord(f.traceStart));
        }
        for (size_t k = 0; k < gpus_.size(); ++k) {
            CudaDeviceGuard guard(gpus_[k]->Device());
            // A GPU's framebuffer holds its last band until the display GPU has gathered it.
            if (k > 0 && traced_ > 0) RT_CUDA_CHECK(cudaStreamWaitEvent(0, previous.gathered));
            RT_CUDA_CHECK(cudaEventRecord(f.bandStart[k]));
            gpus_[k]->TraceBand(scene, settings, f.bands[k], stats != nullptr);
            RT_CUDA_CHECK(cudaEventRecord(f.bandEnd[k]));
        }
        Gather(f, settings.width);
        f.frame = ++traced_;
        f.pending = true;
        f.counted = stats != nullptr;
        if (image) {  // waits for the frame: its times, and the rays every GPU counted
            {
                CudaDeviceGuard guard(Display());
                const size_t pixels = size_t(settings.width) * settings.height;
                image->width = settings.width;
                image->height = settings.height;
                image->pixels.resize(pixels);
                RT_CUDA_CHECK(cudaMemcpy(image->pixels.data(), gpus_[0]->DeviceFrame(),
                                         pixels * sizeof(vec3), cudaMemcpyDeviceToHost));
            }
            Collect(f);
            if (stats) stats->rays = times_.rays;
        }
        SplitFrame& other = frames_[1 - current_];
        if (other.pending) {
            CudaDeviceGuard guard(Display());
            if (cudaEventQuery(other.gathered) == cudaSuccess) Collect(other);
        }
    }

    void Finish() override {
        SplitFrame& other = frames_[1 - current_];
        if (other.pending) Collect(other);
        if (frames_[current_].pending) Collect(frames_[current_]);
        for (const auto& gpu : gpus_) gpu->Finish();
    }

    bool Pick(const Ray& ray, SceneHit* hit) override { return gpus_[0]->Pick(ray, hit); }
    const FrameTimes& Times() const override { return times_; }
    const vec3* DeviceFrame() const override { return gpus_[0]->DeviceFrame(); }
    Tlas CurrentTlas() const override { return gpus_[0]->CurrentTlas(); }

  private:
    int Display() const { return gpus_[0]->Device(); }

    // Peer access from the display GPU to each other GPU (the gather) and back (the TLAS copies),
    // where the hardware has it; elsewhere the copies go through host memory.
    void EnablePeerAccess() {
        for (size_t k = 1; k < gpus_.size(); ++k) {
            const int a = Display(), b = gpus_[k]->Device();
            if (a == b) continue;
            for (const auto& [from, to] : {std::pair{a, b}, std::pair{b, a}}) {
                int can = 0;
                RT_CUDA_CHECK(cudaDeviceCanAccessPeer(&can, from, to));
                if (!can) continue;
                CudaDeviceGuard guard(from);
                const cudaError_t status = cudaDeviceEnablePeerAccess(to, 0);
                if (status == cudaErrorPeerAccessAlreadyEnabled) {
                    cudaGetLastError();  // clears it: enabled is what was asked for
                } else {
                    RT_CUDA_CHECK(status);
                }
            }
        }
    }

    // Each other GPU's band into the display GPU's framebuffer once that GPU has traced it.
    void Gather(const SplitFrame& f, uint32_t width) {
        CudaDeviceGuard guard(Display());
        vec3* target = gpus_[0]->Framebuffer();
        for (size_t k = 1; k < gpus_.size(); ++k) {
            const RowBand band = f.bands[k];
            if (band.Rows() == 0) continue;
            RT_CUDA_CHECK(cudaStreamWaitEvent(0, f.bandEnd[k]));
            const size_t first = size_t(band.begin) * width;
            RT_CUDA_CHECK(cudaMemcpyPeerAsync(target + first, Display(),
                                              gpus_[k]->Framebuffer() + first, gpus_[k]->Device(),
                                              size_t(band.Rows()) * width * sizeof(vec3)));
        }
        RT_CUDA_CHECK(cudaEventRecord(f.gathered));
    }

    // Reads a split frame's times (waiting for it if need be) and moves the shares by them.
    void Collect(SplitFrame& f) {
        FrameTimes t;
        {
            CudaDeviceGuard guard(Display());
            RT_CUDA_CHECK(cudaEventSynchronize(f.gathered));
            gpus_[0]->TimesOf(f.frame, &t);
            t.traceMs = Elapsed(f.traceStart, f.gathered);
        }
        t.frame = f.frame;
        t.gpus = uint32_t(gpus_.size());
        t.rays = 0;
        std::vector<double> ms(gpus_.size());
        for (size_t k = 0; k < gpus_.size(); ++k) {
            CudaDeviceGuard guard(gpus_[k]->Device());
            ms[k] = Elapsed(f.bandStart[k], f.bandEnd[k]);
            t.gpuTraceMs[k] = ms[k];
            t.gpuRows[k] = f.bands[k].Rows();
            FrameTimes own;
            if (f.counted && gpus_[k]->TimesOf(f.frame, &own)) t.rays += own.rays;
        }
        split_.Report(f.bands, ms);
        f.pending = false;
        if (t.frame > times_.frame) times_ = t;
    }

    std::vector<std::unique_ptr<GpuBandRenderer>> gpus_;  // [0] on the display GPU
    bool copiesTlas_ = false;
    FrameSplit split_;
    SplitFrame frames_[2];
    uint32_t current_ = 1;  // the first frame takes set 0
    uint64_t traced_ = 0;
    FrameTimes times_;
};

}  // namespace

std::unique_ptr<FrameRenderer> MakeMultiGpuFrameRenderer(const RenderScene& scene,
                                                         TlasPolicy policy,
                                                         BlasRebuildPolicy blasPolicy,
                                                         const GpuSplit& gpus) {
    return std::make_unique<MultiGpuFrameRenderer>(scene, policy, blasPolicy, gpus);
}

}  // namespace rtrt
