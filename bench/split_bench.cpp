// `rtrt bench split`: split-frame rendering's scaling over the GPUs of one host
// (multi_gpu_frame_renderer.h). Whole frames of the paper scene (full dragon), of an instance
// grid of dragon res4 whose every record moves each frame, and of demo_1000_instances, on 1, 2, 4
// and 8 GPUs (those the machine has), at 1920x1080 and 3840x2160, with the TLAS built on every
// GPU or copied from the display GPU. The frame is timed from the renderer's update to the image
// gathered on the display GPU (the scene's own animation on the host is outside it).
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_commands.h"
#include "bench/bench_report.h"
#include "engine/core/error.h"
#include "engine/core/timer.h"
#include "engine/render_rt/frame_renderer.h"
#include "game/assets/model_dir.h"
#include "game/assets/procedural_shapes.h"
#include "game/runtime/world.h"
#include "game/scene/paper_scene.h"
#include "game/scene/scene_file.h"

namespace rtrt {
namespace {

struct SplitBenchOptions {
    std::vector<std::string> scenes{"paper", "grid", "demo_1000_instances"};
    std::vector<uint32_t> gpus{1, 2, 4, 8};
    std::vector<std::string> sizes{"1920x1080", "3840x2160"};
    std::vector<std::string> tlas{"build", "copy"};
    uint32_t gridInstances = 100000;
    int frames = 100;
    int warmup = 20;
    bool oneGpu = false;
    std::string output;
};

// A scene as the benchmark plays it: each Advance moves it one frame on.
class BenchScene {
  public:
    virtual ~BenchScene() = default;
    virtual const RenderScene& Scene() const = 0;
    virtual SceneChanges Advance() = 0;
};

// The paper's scene, still.
class StillScene final : public BenchScene {
  public:
    explicit StillScene(RenderScene scene) : scene_(std::move(scene)) {}
    const RenderScene& Scene() const override { return scene_; }
    SceneChanges Advance() override { return {}; }

  private:
    RenderScene scene_;
};

// A cube of side^3 >= n dragons as `rtrt bench grid` places them, every one turning and swaying
// each frame.
class GridScene final : public BenchScene {
  public:
    GridScene(std::shared_ptr<const Blas> dragon, uint32_t n)
        : scene_(MakePaperScene(std::move(dragon))),
          side_(uint32_t(std::ceil(std::cbrt(double(n)) - 1e-9))) {
        const float h = 0.75f * float(side_);
        scene_.camera.position = vec3(0.0f, 0.0f, 3.2f * h + 2.0f);
        const Instance first = scene_.instances[0];
        scene_.instances.assign(n, first);
        changed_.resize(n);
        for (uint32_t i = 0; i < n; ++i) changed_[i] = i;
        Place();
    }
    const RenderScene& Scene() const override { return scene_; }
    SceneChanges Advance() override {
        time_ += 1.0f / 60.0f;
        Place();
        return {changed_, false, {}};
    }

  private:
    void Place() {
        const float half = 0.5f * float(side_ - 1);
        for (uint32_t i = 0; i < scene_.instances.size(); ++i) {
            const vec3 cell(float(i % side_), float((i / side_) % side_),
                            float(i / (side_ * side_)));
            const vec3 t = 1.5f * (cell - vec3(half)) + vec3(0.2f * std::sin(time_ + i), 0, 0);
            const glm::mat4 m = glm::rotate(glm::translate(glm::mat4(1.0f), t),
                                            time_ + 0.37f * float(i), vec3(0, 1, 0));
            SetTransform(scene_.instances[i], m);
        }
    }

    RenderScene scene_;
    uint32_t side_;
    float time_ = 0.0f;
    std::vector<uint32_t> changed_;
};

// A scene file played by the runtime.
class PlayedScene final : public BenchScene {
  public:
    explicit PlayedScene(const LoadedScene& loaded) : world_(loaded) {}
    const RenderScene& Scene() const override { return world_.Scene(); }
    SceneChanges Advance() override {
        world_.Advance(1.0f / 60.0f);
        return world_.Changes();
    }

  private:
    World world_;
};

std::shared_ptr<const Blas> BenchBlas(const std::string& model, float extent) {
    TriangleMesh mesh;
    if (!LoadBenchModel(model, &mesh))
        throw InputError(
            ModelDir() + "/dragon_vrip" + (model == "dragon" ? "" : model.substr(6)) + ".ply.gz",
            "", "missing; run rtrt fetch-models");
    FitMesh(mesh, extent);
    return std::make_shared<const Blas>(BuildTriangleBlas(mesh));
}

struct Row {
    std::string scene, size, tlas;
    uint32_t gpus = 1;
    double frameMs = 0, traceMs = 0;
    std::vector<double> gpuTraceMs;
    std::vector<uint32_t> gpuRows;
};

Row RunOne(BenchScene& scene, const RenderSettings& settings, const GpuSplit& split,
           const SplitBenchOptions& o) {
    const std::unique_ptr<FrameRenderer> renderer =
        MakeFrameRenderer(Backend::kCuda, scene.Scene(), {}, {}, split);
    std::vector<double> frame, trace;
    std::vector<std::vector<double>> perGpu(FrameTimes::kMaxGpus);
    Row row;
    for (int f = 0; f < o.warmup + o.frames; ++f) {
        const SceneChanges changes = scene.Advance();
        Stopwatch timer;
        renderer->Update(scene.Scene(), changes);
        renderer->Trace(scene.Scene(), settings, nullptr);
        renderer->Finish();
        const double ms = timer.Milliseconds();
        if (f < o.warmup) continue;
        const FrameTimes& t = renderer->Times();
        frame.push_back(ms);
        trace.push_back(t.traceMs);
        for (uint32_t g = 0; g < t.gpus; ++g) perGpu[g].push_back(t.gpuTraceMs[g]);
        row.gpuRows.assign(t.gpuRows.begin(), t.gpuRows.begin() + t.gpus);
    }
    row.frameMs = Median(frame);
    row.traceMs = Median(trace);
    for (uint32_t g = 0; g < row.gpuRows.size(); ++g) row.gpuTraceMs.push_back(Median(perGpu[g]));
    return row;
}

void RunSplitBench(const SplitBenchOptions& o) {
    const uint32_t present = CudaDeviceCount();
    nlohmann::json report;
    report["machine"] = BenchMachine(true);
    report["gpus_present"] = present;
    report["one_gpu"] = o.oneGpu;
    report["timing"] =
        "medians over --frames frames after --warmup; frame_ms: host clock from the frame "
        "renderer's update to the frame gathered on the display GPU; trace_ms: CUDA events on "
        "the display GPU from the trace's start to the gathered frame; gpu_trace_ms: each GPU's "
        "own band";
    std::printf("rtrt bench split: %u GPU%s here%s, medians over %d frames, ms\n", present,
                present == 1 ? "" : "s",
                o.oneGpu ? " (--one-gpu: each split is N renderers of GPU 0)" : "", o.frames);
    std::printf("%-22s %10s %5s %6s %9s %9s %8s  %s\n", "scene", "size", "gpus", "tlas", "frame",
                "trace", "speedup", "per GPU: trace ms (rows)");
    std::shared_ptr<const Blas> dragon, dragonRes4;
    for (const std::string& name : o.scenes) {
        std::unique_ptr<LoadedScene> loaded;
        if (name == "paper" && !dragon) dragon = BenchBlas("dragon", 5.0f);
        if (name == "grid" && !dragonRes4) dragonRes4 = BenchBlas("dragon_res4", 1.0f);
        if (name != "paper" && name != "grid")
            loaded = std::make_unique<LoadedScene>(LoadSceneFile(ScenePathFor(name)));
        // A fresh copy of the scene for every run, so that each starts from the same frame.
        const auto make = [&]() -> std::unique_ptr<BenchScene> {
            if (name == "paper") return std::make_unique<StillScene>(MakePaperScene(dragon));
            if (name == "grid") return std::make_unique<GridScene>(dragonRes4, o.gridInstances);
            return std::make_unique<PlayedScene>(*loaded);
        };
        for (const std::string& size : o.sizes) {
            RenderSettings settings;
            ParseSize(size, &settings.width, &settings.height);
            settings.maxDepth = make()->Scene().maxDepth;
            double single = 0.0;
            for (uint32_t n : o.gpus) {
                if (!o.oneGpu && n > present) {
                    std::printf("%-22s %10s %5u  skipped: this machine has %u GPU%s\n",
                                name.c_str(), size.c_str(), n, present, present == 1 ? "" : "s");
                    continue;
                }
                for (const std::string& tlas : o.tlas) {
                    if (n == 1 && tlas != o.tlas.front()) continue;  // nothing to share
                    GpuSplit split;
                    for (uint32_t g = 0; g < n && n > 1; ++g)
                        split.devices.push_back(o.oneGpu ? 0 : int(g));
                    split.tlas = tlas == "copy" ? GpuSplit::Tlas::kCopyFromDisplay
                                                : GpuSplit::Tlas::kBuildOnEach;
                    const std::unique_ptr<BenchScene> scene = make();
                    Row r = RunOne(*scene, settings, split, o);
                    r.scene = name;
                    r.size = size;
                    r.gpus = n;
                    r.tlas = n == 1 ? "-" : tlas;
                    if (n == 1) single = r.frameMs;
                    const double speedup = single > 0 ? single / r.frameMs : 0.0;
                    std::string per;
                    for (size_t g = 0; g < r.gpuTraceMs.size(); ++g) {
                        char cell[48];
                        std::snprintf(cell, sizeof(cell), "%s%.3f (%u)", g ? "  " : "",
                                      r.gpuTraceMs[g], r.gpuRows[g]);
                        per += cell;
                    }
                    std::printf("%-22s %10s %5u %6s %9.3f %9.3f %7.2fx  %s\n", name.c_str(),
                                size.c_str(), n, r.tlas.c_str(), r.frameMs, r.traceMs, speedup,
                                per.c_str());
                    std::fflush(stdout);
                    report["rows"].push_back({{"scene", r.scene},
                                              {"size", r.size},
                                              {"gpus", r.gpus},
                                              {"tlas", r.tlas},
                                              {"frame_ms", r.frameMs},
                                              {"trace_ms", r.traceMs},
                                              {"speedup_frame", speedup},
                                              {"gpu_trace_ms", r.gpuTraceMs},
                                              {"gpu_rows", r.gpuRows}});
                }
            }
        }
    }
    WriteReportIfNamed(o.output, report);
}

}  // namespace

void AddSplitBench(CLI::App& bench, int* exitCode) {
    auto o = std::make_shared<SplitBenchOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "split", "Split-frame scaling over the GPUs of this host (--gpus of render and play)");
    cmd->add_option("--scenes", o->scenes,
                    "paper (full dragon), grid (instances of dragon res4, all moving) and scene "
                    "files or names")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--gpus", o->gpus, "GPU counts to split over (more than present are skipped)")
        ->delimiter(',')
        ->check(CLI::Range(1u, FrameTimes::kMaxGpus))
        ->capture_default_str();
    cmd->add_option("--sizes", o->sizes, "Frame sizes WIDTHxHEIGHT")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--tlas", o->tlas,
                    "build: every GPU builds the TLAS; copy: the display GPU builds it and the "
                    "others copy it")
        ->delimiter(',')
        ->check(CLI::IsMember({"build", "copy"}))
        ->capture_default_str();
    cmd->add_option("--grid-instances", o->gridInstances, "Instances of the grid scene")
        ->check(CLI::Range(1u, 4000000u))
        ->capture_default_str();
    cmd->add_option("--frames", o->frames, "Timed frames per row")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    cmd->add_option("--warmup", o->warmup, "Untimed frames first")
        ->check(CLI::Range(0, 100000))
        ->capture_default_str();
    cmd->add_flag("--one-gpu", o->oneGpu,
                  "Split over N renderers of GPU 0: the split's own cost on a machine of one GPU");
    cmd->add_option("-o,--output", o->output, "Write the results as JSON here")
        ->check(WritableFile());
    cmd->callback([o, exitCode] {
        std::string why;
        if (!CudaBackendAvailable(&why))
            throw InputError("bench split", "", why + "; the split is of frames over GPUs only");
        for (const std::string& size : o->sizes) {
            uint32_t w, h;
            ParseSize(size, &w, &h);
        }
        RunSplitBench(*o);
        *exitCode = kExitOk;
    });
}

}  // namespace rtrt
