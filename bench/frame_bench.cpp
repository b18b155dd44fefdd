// `rtrt bench frame`: whole frames of played scenes, every stage timed: simulation (physics,
// animation, transforms), extraction, and then on the GPU the deformation of deforming meshes
// and their BLAS refits or rebuilds, the upload of changed instance records, the TLAS and the
// trace (CUDA events), or on the CPU the TLAS and the trace. Each scene is played twice:
//   - one frame at a time: the frame time is the wall clock from the start of the simulation to
//     the finished image on the device (a frame's latency), and the stages are timed;
//   - pipelined, as a game loop overlaps them: the host simulates and extracts frame N+1 while
//     the device still deforms and traces frame N (Trace returns with the frame in flight; the
//     frame renderer keeps at most two queued). The frame time is then the interval between frames
//     in steady state, what a player sees as the frame rate.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "bench/backend_option.h"
#include "bench/bench_commands.h"
#include "bench/bench_report.h"
#include "engine/core/error.h"
#include "engine/core/output_file.h"
#include "engine/core/timer.h"
#include "engine/render_rt/frame_renderer.h"
#include "game/runtime/world.h"
#include "game/scene/scene_file.h"

namespace rtrt {
namespace {

struct FrameBenchOptions {
    std::vector<std::string> scenes;
    std::string backend = "auto";
    std::string size;
    int frames = 300;
    int warmup = 30;
    uint32_t traceBands = 1;
    std::string gpus = "1";
    GpuSplit split;  // what gpus names
    std::string physicsSolver = "cpu";
    std::string traversal = "auto";
    std::string output;
};

struct StageSamples {
    std::vector<double> simulate, extract, deform, blas, upload, tlas, trace, frame, instances,
        uploaded, tlasRebuilt, singleLoop;
};

// Frame intervals of the same scene played pipelined from its start: each loop pass advances
// the world and queues its frame without waiting for it; the renderer waits, when it must, for
// the frame two before. The pass's wall time in steady state is the interval between frames.
std::vector<double> PipelinedIntervals(const LoadedScene& loaded, const RenderSettings& settings,
                                       bool gpu, const FrameBenchOptions& o) {
    World world(loaded);
    ApplyPhysicsSolver(o.physicsSolver, world);
    const std::unique_ptr<FrameRenderer> renderer =
        MakeFrameRenderer(gpu ? Backend::kCuda : Backend::kCpu, world.Scene(), {}, {}, o.split);
    std::vector<double> intervals;
    Stopwatch pass;
    for (int f = 0; f < o.warmup + o.frames; ++f) {
        world.Advance(1.0f / 60.0f);
        renderer->Update(world.Scene(), world.Changes());
        renderer->Trace(world.Scene(), settings, nullptr);
        if (f >= o.warmup) intervals.push_back(pass.Milliseconds());
        pass.Restart();
    }
    renderer->Finish();
    return intervals;
}

nlohmann::json RunScene(const std::string& path, const LoadedScene& loaded,
                        const FrameBenchOptions& o) {
    RenderSettings settings;
    settings.width = loaded.width.value_or(1280);
    settings.height = loaded.height.value_or(720);
    if (!o.size.empty()) ParseSize(o.size, &settings.width, &settings.height);
    settings.maxDepth = loaded.scene.maxDepth;
    settings.traceBands = o.traceBands;
    ParseTraversalForm(o.traversal, &settings.traversal);  // checked by the option
    const bool gpu = o.backend == "cuda";
    World world(loaded);
    ApplyPhysicsSolver(o.physicsSolver, world);
    const std::unique_ptr<FrameRenderer> renderer =
        MakeFrameRenderer(gpu ? Backend::kCuda : Backend::kCpu, world.Scene(), {}, {}, o.split);
    StageSamples s;
    RenderStats stats;
    for (int f = 0; f < o.warmup + o.frames; ++f) {
        Stopwatch frameTimer;
        const FrameStats fs = world.Advance(1.0f / 60.0f);
        renderer->Update(world.Scene(), world.Changes());
        renderer->Trace(world.Scene(), settings, nullptr, f == 0 ? &stats : nullptr);
        // The frame ends when its image is finished; then its stage times are known.
        renderer->Finish();
        const FrameTimes& t = renderer->Times();
        if (f == 0) stats.rays = t.rays;
        const double frameMs = frameTimer.Milliseconds();
        if (f < o.warmup) continue;
        s.simulate.push_back(fs.simulateMs);
        s.extract.push_back(fs.extractMs);
        s.deform.push_back(t.deformMs);
        s.blas.push_back(t.blasMs);
        s.upload.push_back(t.uploadMs);
        s.tlas.push_back(t.tlasMs);
        s.trace.push_back(t.traceMs);
        s.frame.push_back(frameMs);
        s.instances.push_back(double(world.Scene().instances.size()));
        s.uploaded.push_back(double(fs.extracted));
        s.tlasRebuilt.push_back(t.tlasRebuilt ? 1.0 : 0.0);
        s.singleLoop.push_back(t.singleLoop ? 1.0 : 0.0);
    }
    const std::vector<double> pipelined = PipelinedIntervals(loaded, settings, gpu, o);
    nlohmann::json row = {
        {"scene", std::filesystem::path(path).filename().string()},
        {"width", settings.width},
        {"height", settings.height},
        {"instances", world.Scene().instances.size()},
        {"changed_per_frame", Median(s.uploaded)},
        {"rays_first_frame", stats.rays},
        {"simulate_ms", Median(s.simulate)},
        {"extract_ms", Median(s.extract)},
        {"deform_ms", Median(s.deform)},
        {"blas_ms", Median(s.blas)},
        {"upload_ms", Median(s.upload)},
        {"tlas_ms", Median(s.tlas)},
        {"tlas_ms_mean", Mean(s.tlas)},
        {"tlas_rebuilt_share", Mean(s.tlasRebuilt)},
        {"trace_ms", Median(s.trace)},
        {"trace_ms_mean", Mean(s.trace)},
        {"single_loop_share", Mean(s.singleLoop)},
        {"frame_ms", Median(s.frame)},
        {"frame_ms_max", *std::max_element(s.frame.begin(), s.frame.end())},
        {"pipelined_frame_ms", Median(pipelined)},
        {"pipelined_frame_ms_max", *std::max_element(pipelined.begin(), pipelined.end())}};
    std::printf("%-26s %9s %9zu %8.0f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f\n",
                row["scene"].get<std::string>().c_str(),
                (std::to_string(settings.width) + "x" + std::to_string(settings.height)).c_str(),
                world.Scene().instances.size(), Median(s.uploaded), Median(s.simulate),
                Median(s.extract), Median(s.deform), Median(s.blas), Median(s.upload),
                Median(s.tlas), Median(s.trace), Median(s.frame), Median(pipelined));
    return row;
}

void RunFrameBench(const FrameBenchOptions& o) {
    // Every scene is read before any is played, so that a bad file ends the run before the
    // first measurement rather than after it.
    std::vector<LoadedScene> loadedScenes;
    loadedScenes.reserve(o.scenes.size());
    for (const std::string& path : o.scenes) loadedScenes.push_back(LoadSceneFile(path));
    RefuseOutputOverAsset(o.output);
    const bool gpu = o.backend == "cuda";
    nlohmann::json report;
    report["machine"] = BenchMachine(gpu);
    report["backend"] = o.backend;
    report["trace_bands"] = o.traceBands;
    report["gpus"] = o.split.devices.empty() ? 1 : o.split.devices.size();
    report["physics_solver"] = o.physicsSolver;
    report["traversal"] = o.traversal;
    report["timing"] =
        "medians over --frames frames at 60 fps after --warmup frames; GPU stages by CUDA events, "
        "simulation and extraction and the whole frame by the CPU clock (frame_ms: one frame at "
        "a time, from the start of its simulation until its image is finished in device memory; "
        "pipelined_frame_ms: the interval between frames when the host simulates frame N+1 while "
        "the device works on frame N); tlas_rebuilt_share: the share of timed frames whose TLAS "
        "was built afresh rather than refit or left alone; single_loop_share: the share traced "
        "with "
        "the single loop over both levels rather than the nested traversal; *_ms_mean: means over "
        "the same frames";
    std::printf("rtrt bench frame (%s back end), medians over %d frames, ms\n", o.backend.c_str(),
                o.frames);
    std::printf("%-26s %9s %9s %8s %9s %9s %9s %9s %9s %9s %9s %9s %9s\n", "scene", "size",
                "instances", "changed", "simulate", "extract", "deform", "BLAS", "upload", "TLAS",
                "trace", "frame", "pipelined");
    for (size_t i = 0; i < o.scenes.size(); ++i) {
        report["rows"].push_back(RunScene(o.scenes[i], loadedScenes[i], o));
    }
    WriteReportIfNamed(o.output, report);
}

}  // namespace

void AddFrameBench(CLI::App& bench, int* exitCode) {
    auto o = std::make_shared<FrameBenchOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "frame", "Whole frames of played scenes: simulation, extraction, upload, TLAS, trace");
    cmd->add_option("scenes", o->scenes, "Scene files or names to play")->required();
    AddBackendOption(cmd, &o->backend);
    cmd->add_option("--size", o->size, "WIDTHxHEIGHT (default: the scene's image size)");
    cmd->add_option("--frames", o->frames, "Timed frames per scene")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    cmd->add_option("--warmup", o->warmup, "Untimed frames first")
        ->check(CLI::Range(0, 100000))
        ->capture_default_str();
    cmd->add_option("--trace-bands", o->traceBands,
                    "CUDA: trace each frame in this many row bands, each on its own stream")
        ->check(CLI::Range(1, 64))
        ->capture_default_str();
    AddGpusOption(cmd, &o->gpus);
    AddPhysicsSolverOption(cmd, &o->physicsSolver);
    AddTraversalOption(cmd, &o->traversal);
    cmd->add_option("-o,--output", o->output, "Write the results as JSON here")
        ->check(WritableFile());
    cmd->callback([o, exitCode] {
        const Backend backend = ResolveBackendOption(&o->backend);
        o->split = ResolveGpus(o->gpus, backend);
        CheckTraversalBackend(o->traversal, backend);
        if (backend != Backend::kCuda && o->traceBands > 1)
            throw InputError("--trace-bands", std::to_string(o->traceBands),
                             "row bands are CUDA streams and need the CUDA back end; use "
                             "--backend cuda or leave --trace-bands out");
        // Checked before the report's header, as the other options.
        if (!o->size.empty()) {
            uint32_t width = 0, height = 0;
            ParseSize(o->size, &width, &height);
        }
        CheckPhysicsSolver(o->physicsSolver);
        RunFrameBench(*o);
        *exitCode = kExitOk;
    });
}

}  // namespace rtrt
