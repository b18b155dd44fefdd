// `rtrt bench cpu`: BLAS build time and SAH cost per builder, and CPU frame time and rays per
// second on the paper scene (paper_scene.h), for the cube, the teapot and the dragons.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_commands.h"
#include "bench/bench_report.h"
#include "bench/build_commit.h"
#include "bench/ecs_benchmark.h"
#include "bench/gpu_trace_timing.h"
#include "bench/instance_grid_bench.h"
#include "engine/core/error.h"
#include "engine/core/output_file.h"
#include "engine/core/timer.h"
#include "engine/render_rt/frame_renderer.h"
#include "engine/render_rt/renderer.h"
#include "game/assets/mesh_io.h"
#include "game/assets/model_dir.h"
#include "game/assets/procedural_shapes.h"
#include "game/assets/teapot.h"
#include "game/cli/cli_options.h"
#include "game/runtime/world.h"
#include "game/scene/paper_scene.h"
#include "game/scene/scene_file.h"

namespace rtrt {

std::string BenchModelFile(const std::string& name) {
    if (name == "cube") return "";
    if (name == "teapot") return ModelDir() + "/teapot.inc";
    const std::string suffix = name == "dragon" ? "" : name.substr(6);  // "_res4"
    return ModelDir() + "/dragon_vrip" + suffix + ".ply.gz";
}

void SkipMissingModel(nlohmann::json& report, const std::string& name) {
    const std::string file = BenchModelFile(name);
    std::printf("%-12s skipped: %s missing (run rtrt fetch-models)\n", name.c_str(), file.c_str());
    report["skipped"].push_back({{"model", name}, {"reason", file + " missing"}});
}

void DropRepeats(std::vector<std::string>* names) {
    std::vector<std::string> once;
    for (const std::string& name : *names)
        if (std::find(once.begin(), once.end(), name) == once.end()) once.push_back(name);
    *names = std::move(once);
}

void CheckBenchModels(const std::vector<std::string>& models, const std::string& output) {
    for (const std::string& name : models)
        if (const std::string file = BenchModelFile(name);
            !output.empty() && !file.empty() && NameTheSameFile(output, file))
            throw InputError("--output", output,
                             "is also the file of the model " + name + " (" + file +
                                 "), which would be written over; name another file");
    std::string names;
    for (const std::string& name : models) {
        const std::string file = BenchModelFile(name);
        if (file.empty() || std::filesystem::exists(file)) return;
        names += (names.empty() ? "" : ", ") + name;
    }
    throw InputError(ModelDir(), "--models",
                     "none of the models asked for is there (" + names +
                         "); run rtrt fetch-models, or set RTRT_MODEL_DIR to where they are");
}

bool LoadBenchModel(const std::string& name, TriangleMesh* mesh) {
    const std::string path = BenchModelFile(name);
    if (path.empty()) {
        *mesh = MakeBoxMesh(vec3(1.0f));
    } else if (!std::filesystem::exists(path)) {
        return false;
    } else if (name == "teapot") {
        *mesh = TessellateTeapot(path, 6);
    } else {
        *mesh = LoadMesh(path);
    }
    FitMesh(*mesh, 5.0f);
    return true;
}

std::vector<BenchModel> LoadBenchModels(const std::vector<std::string>& names) {
    std::vector<BenchModel> models;
    for (const std::string& name : names) {
        BenchModel& model = models.emplace_back();
        model.name = name;
        Stopwatch timer;
        TriangleMesh mesh;
        if (LoadBenchModel(name, &mesh)) model.mesh = std::move(mesh);
        model.loadMs = timer.Milliseconds();
    }
    return models;
}

CLI::Option* AddModelsOption(CLI::App* command, std::vector<std::string>* models) {
    return command
        ->add_option("--models", *models,
                     "cube, teapot, dragon_res4, dragon_res3, dragon_res2, dragon")
        ->check(CLI::IsMember(
            {"cube", "teapot", "dragon_res4", "dragon_res3", "dragon_res2", "dragon"}))
        ->delimiter(',')
        ->capture_default_str();
}

namespace {

struct BenchOptions {
    int frames = 7;
    int gpuFrames = 200;
    std::string output;
    std::vector<std::string> models{"cube",        "teapot",      "dragon_res4",
                                    "dragon_res3", "dragon_res2", "dragon"};
    std::vector<std::string> builders{"binned", "sweep", "centroid"};
    std::vector<std::string> gpuBuilders{"binned"};
};

std::string CommandOutput(const char* command) {
    std::string out;
    if (FILE* pipe = popen(command, "r")) {
        char buffer[256];
        while (fgets(buffer, sizeof(buffer), pipe)) out += buffer;
        pclose(pipe);
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
    return out;
}

nlohmann::json MachineInfo() {
    nlohmann::json m;
    m["cpu"] = CommandOutput("grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //'");
    m["threads"] = std::thread::hardware_concurrency();
    m["host"] = CommandOutput("hostname");
    // The commit the binary was built from ("-dirty" with changes not committed); RTRT_COMMIT
    // overrides it. The commit of the folder the command ran in had named whatever repository
    // that was.
    const char* commit = std::getenv("RTRT_COMMIT");
    m["commit"] = commit && *commit ? std::string(commit) : std::string(RTRT_BUILD_COMMIT);
    std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof(date), "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    m["date"] = date;
    return m;
}

void RunBench(const BenchOptions& o) {
    nlohmann::json report;
    report["machine"] = MachineInfo();
    report["scene"] = "paper scene, 1920x1080, max depth 2, one ray per pixel centre";
    std::printf("rtrt bench cpu: %s, %u threads\n",
                report["machine"]["cpu"].get<std::string>().c_str(),
                std::thread::hardware_concurrency());
    std::printf("%-12s %10s %-9s %10s %9s %8s | %10s %8s %9s\n", "model", "triangles", "builder",
                "build ms", "SAH cost", "nodes", "frame ms", "M rays", "M rays/s");
    for (const BenchModel& model : LoadBenchModels(o.models)) {
        const std::string& name = model.name;
        if (!model.mesh) {
            SkipMissingModel(report, name);
            continue;
        }
        const TriangleMesh& mesh = *model.mesh;
        nlohmann::json row;
        row["model"] = name;
        row["triangles"] = mesh.indices.size();
        row["load_ms"] = model.loadMs;
        std::shared_ptr<const Blas> binned;
        for (const std::string& builderName : o.builders) {
            BvhBuildOptions options;
            ParseBuilder(builderName, &options.builder);
            std::vector<double> times;
            Blas blas;
            Stopwatch total;
            do {
                Stopwatch t;
                blas = BuildTriangleBlas(mesh, options);
                times.push_back(t.Milliseconds());
            } while (times.size() < 5 && total.Milliseconds() < 1500.0);
            const BvhStats stats = ComputeStats(blas.nodes);
            row["builders"][builderName] = {
                {"build_ms", Median(times)}, {"sah_cost", stats.sahCost},
                {"nodes", stats.nodeCount},  {"max_depth", stats.maxDepth},
                {"bytes", blas.Bytes()},     {"runs", times.size()}};
            std::printf("%-12s %10zu %-9s %10.1f %9.2f %8u |", name.c_str(), mesh.indices.size(),
                        builderName.c_str(), Median(times), stats.sahCost, stats.nodeCount);
            std::fflush(stdout);
            // Each builder's tree traces the paper scene, so SAH cost can be read against time.
            const RenderScene scene = MakePaperScene(std::make_shared<const Blas>(std::move(blas)));
            RenderSettings settings{kPaperWidth, kPaperHeight, kPaperMaxDepth};
            RenderStats renderStats;
            Image frame;
            RenderInto(scene, settings, frame, &renderStats);  // warm-up
            std::vector<double> frameTimes;
            for (int i = 0; i < o.frames; ++i) {
                Stopwatch t;
                RenderInto(scene, settings, frame, &renderStats);
                frameTimes.push_back(t.Milliseconds());
            }
            const double frameMs = Median(frameTimes);
            const double mrays = double(renderStats.rays) * 1e-6;
            row["builders"][builderName]["frame_ms"] = frameMs;
            row["builders"][builderName]["rays"] = renderStats.rays;
            row["builders"][builderName]["mrays_per_s"] = mrays / (frameMs * 1e-3);
            std::printf(" %10.1f %8.2f %9.1f\n", frameMs, mrays, mrays / (frameMs * 1e-3));
        }
        report["models"].push_back(row);
    }
    WriteReportIfNamed(o.output, report);
}

// The paper scene on the GPU: the trace kernel timed with CUDA events, median of many frames.
void RunGpuBench(const BenchOptions& o) {
    nlohmann::json report;
    report["machine"] = MachineInfo();
    report["machine"]["gpu"] = CommandOutput(
        "nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null");
    report["scene"] = "paper scene, 1920x1080, max depth 2, one ray per pixel centre";
    report["timing"] = "CUDA events around the trace kernel, 20 warm-up frames, median of the rest";
    std::printf("rtrt bench gpu: %s\n", report["machine"]["gpu"].get<std::string>().c_str());
    std::printf("%-12s %10s %-9s %10s %10s %8s %9s %10s\n", "model", "triangles", "builder",
                "median ms", "min ms", "M rays", "G rays/s", "B/tri");
    for (const BenchModel& model : LoadBenchModels(o.models)) {
        const std::string& name = model.name;
        if (!model.mesh) {
            SkipMissingModel(report, name);
            continue;
        }
        const TriangleMesh& mesh = *model.mesh;
        for (const std::string& builderName : o.gpuBuilders) {
            BvhBuildOptions options;
            ParseBuilder(builderName, &options.builder);
            auto blas = std::make_shared<const Blas>(BuildTriangleBlas(mesh, options));
            const size_t blasBytes = blas->DeviceBytes();
            const float sahCost = SahCost(blas->nodes);
            const RenderScene scene = MakePaperScene(blas);
            RenderSettings settings{kPaperWidth, kPaperHeight, kPaperMaxDepth};
            RenderStats stats;
            const std::vector<double> times =
                TimeCudaTrace(scene, settings, 20, o.gpuFrames, &stats);
            const double median = Median(times);
            const double best = *std::min_element(times.begin(), times.end());
            const double grays = double(stats.rays) / (median * 1e-3) * 1e-9;
            const double bytesPerTri = double(blasBytes) / double(mesh.indices.size());
            std::printf("%-12s %10zu %-9s %10.3f %10.3f %8.2f %9.2f %10.1f\n", name.c_str(),
                        mesh.indices.size(), builderName.c_str(), median, best,
                        double(stats.rays) * 1e-6, grays, bytesPerTri);
            report["models"].push_back({{"model", name},
                                        {"triangles", mesh.indices.size()},
                                        {"builder", builderName},
                                        {"sah_cost", sahCost},
                                        {"leaf_slots", blas->PrimCount()},
                                        {"trace_ms_median", median},
                                        {"trace_ms_min", best},
                                        {"frames", times.size()},
                                        {"rays", stats.rays},
                                        {"grays_per_s", grays},
                                        {"blas_bytes", blasBytes},
                                        {"bytes_per_triangle", bytesPerTri}});
        }
    }
    WriteReportIfNamed(o.output, report);
}

}  // namespace

void RunGridBench(const std::vector<uint32_t>& counts, int frames, const std::string& output) {
    TriangleMesh mesh;
    if (!LoadBenchModel("dragon_res4", &mesh))
        throw InputError(ModelDir() + "/dragon_vrip_res4.ply.gz", "",
                         "missing; run rtrt fetch-models");
    FitMesh(mesh, 1.0f);  // the grid's instances have largest extent 1
    auto blas = std::make_shared<const Blas>(BuildTriangleBlas(mesh));
    nlohmann::json report;
    report["machine"] = MachineInfo();
    report["machine"]["gpu"] = CommandOutput(
        "nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null");
    report["scene"] =
        "instance grid of dragon res4, 1920x1080, max depth 2, TLAS rebuilt every frame";
    report["timing"] = "CUDA events per stage, 20 warm-up frames, median of the rest";
    std::printf("rtrt bench grid: %s\n", report["machine"]["gpu"].get<std::string>().c_str());
    std::printf("%10s %10s %10s %10s %10s %10s %8s %8s\n", "instances", "update ms", "TLAS ms",
                "refit ms", "trace ms", "total ms", "M rays", "B/inst");
    for (const InstanceGridRow& r : RunInstanceGridBench(blas, counts, frames)) {
        std::printf("%10u %10.3f %10.3f %10.3f %10.3f %10.3f %8.2f %8.0f\n", r.instances,
                    r.updateMs, r.tlasMs, r.refitMs, r.traceMs, r.totalMs, double(r.rays) * 1e-6,
                    r.bytesPerInstance);
        report["rows"].push_back({{"instances", r.instances},
                                  {"update_ms", r.updateMs},
                                  {"tlas_build_ms", r.tlasMs},
                                  {"tlas_refit_ms", r.refitMs},
                                  {"trace_ms", r.traceMs},
                                  {"total_ms", r.totalMs},
                                  {"rays", r.rays},
                                  {"bytes_per_instance", r.bytesPerInstance},
                                  {"frames", frames}});
    }
    WriteReportIfNamed(output, report);
}

// Runtime cost per stage on a played scene: what a scene does not use must cost ~nothing. Each
// scene is played once per contact solver (cpu, gpu) and thread count (0: TBB's default, every
// core); broad to gpu-pass split the physics step (PhysicsTimes), and "p.thr" is the threads it
// could use (one in a small world: PhysicsSettings::minParallelBodies).
void RunRuntimeBench(const std::vector<std::string>& scenes, int frames,
                     const std::vector<int>& threadCounts,
                     const std::vector<std::string>& solvers) {
    // Every scene is read before any is played, so that a bad file ends the run before the
    // first measurement rather than after it.
    std::vector<LoadedScene> loadedScenes;
    loadedScenes.reserve(scenes.size());
    for (const std::string& path : scenes) loadedScenes.push_back(LoadSceneFile(path));
    std::printf(
        "rtrt bench runtime: medians over %d frames at 60 fps (ms; \"on\": where the contacts "
        "are solved)\n",
        frames);
    std::printf(
        "%-28s %6s %7s %9s %9s %9s %11s %9s %9s %9s %9s %9s %9s %7s %8s %8s %8s %8s %8s %8s "
        "%5s\n",
        "scene", "on", "threads", "instances", "moving", "physics", "animators", "transform",
        "extract", "deform", "BLAS", "TLAS", "contacts", "colours", "broad", "narrow", "solver",
        "integr.", "gpu-copy", "gpu-pass", "p.thr");
    for (size_t sceneIndex = 0; sceneIndex < scenes.size(); ++sceneIndex) {
        const std::string& path = scenes[sceneIndex];
        const LoadedScene& loaded = loadedScenes[sceneIndex];
        for (const std::string& solverName : solvers) {
            for (const int threadCount : threadCounts) {
                const int threads =
                    threadCount > 0 ? threadCount : tbb::this_task_arena::max_concurrency();
                const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                                static_cast<size_t>(threads));
                World world(loaded);
                ApplyPhysicsSolver(solverName, world);
                // The TLAS stage of the CPU back end: its frame renderer's update, without a trace.
                const std::unique_ptr<FrameRenderer> renderer =
                    MakeFrameRenderer(Backend::kCpu, world.Scene());
                std::vector<double> physics, animators, transforms, extract, deform, blas, tlas,
                    moving, contacts, colours, broad, narrow, solver, integrate, gpuCopy, gpuPass,
                    physicsThreads;
                for (int i = 0; i < frames; ++i) {
                    const FrameStats stats = world.Advance(1.0f / 60.0f);
                    renderer->Update(world.Scene(), world.Changes());
                    // A frame's times are published by its trace: a one-pixel one costs nothing
                    // here.
                    RenderSettings onePixel;
                    onePixel.width = onePixel.height = 1;
                    renderer->Trace(world.Scene(), onePixel, nullptr);
                    deform.push_back(renderer->Times().deformMs);
                    blas.push_back(renderer->Times().blasMs);
                    tlas.push_back(renderer->Times().tlasMs);
                    for (const ecs::SystemTiming& t : world.Scheduler().SystemTimings()) {
                        if (t.name == "physics") physics.push_back(t.milliseconds);
                        if (t.name == "animators") animators.push_back(t.milliseconds);
                        if (t.name == "transforms") transforms.push_back(t.milliseconds);
                    }
                    extract.push_back(stats.extractMs);
                    moving.push_back(stats.extracted);
                    contacts.push_back(world.PhysicsStats().lastContacts);
                    colours.push_back(world.PhysicsStats().lastColors);
                    physicsThreads.push_back(world.PhysicsStats().lastThreads);
                    const physics::PhysicsTimes& times = world.PhysicsStats().lastTimes;
                    broad.push_back(times.broadPhaseMs);
                    narrow.push_back(times.narrowPhaseMs);
                    solver.push_back(times.solverMs);
                    integrate.push_back(times.integrateMs);
                    gpuCopy.push_back(times.gpuTransferMs);
                    gpuPass.push_back(times.gpuSolveMs);
                }
                std::printf(
                    "%-28s %6s %7d %9zu %9.0f %9.4f %11.4f %9.4f %9.4f %9.4f %9.4f %9.4f %9.0f "
                    "%7.0f "
                    "%8.3f %8.3f %8.3f %8.3f %8.3f %8.3f %5.0f\n",
                    std::filesystem::path(path).filename().string().c_str(), solverName.c_str(),
                    threads, world.Scene().instances.size(), Median(moving), Median(physics),
                    Median(animators), Median(transforms), Median(extract), Median(deform),
                    Median(blas), Median(tlas), Median(contacts), Median(colours), Median(broad),
                    Median(narrow), Median(solver), Median(integrate), Median(gpuCopy),
                    Median(gpuPass), Median(physicsThreads));
            }
        }
    }
}

void RunEcsBench(uint32_t count) {
    const ecs::EcsBenchResult r = ecs::RunEcsBenchmark(count);
    std::printf("rtrt bench ecs: %u entities (Position + Velocity, every 4th a third component)\n",
                count);
    std::printf("  create  %8.2f ms  (%.1f ns per entity)\n", r.createMs, r.createMs * 1e6 / count);
    std::printf("  iterate %8.2f ms  (2-component view, %.2f ns per entity)\n", r.iterateMs,
                r.iterateMs * 1e6 / count);
    std::printf("  destroy %8.2f ms  (%.1f ns per entity)\n", r.destroyMs,
                r.destroyMs * 1e6 / count);
    std::printf("  checksum %llu (medians of 3 runs)\n", (unsigned long long)r.checksum);
}

void AddBenchCommand(CLI::App& app, int* exitCode) {
    CLI::App* bench = app.add_subcommand("bench", "Benchmarks (see README: Benchmarks)");
    bench->require_subcommand(1);
    // A report's lines are written as they are measured, also into a file or pipe: an interrupt
    // exits at once (_exit), and would drop the rows a full buffer still held.
    bench->preparse_callback([](size_t) { std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ); });
    AddConvertBench(*bench, exitCode, &MachineInfo);
    auto options = std::make_shared<BenchOptions>();
    CLI::App* cpu = bench->add_subcommand(
        "cpu", "BLAS build time and SAH cost per builder, CPU frame time on the paper scene");
    cpu->add_option("--frames", options->frames, "Timed frames per model (median reported)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    AddModelsOption(cpu, &options->models);
    cpu->add_option("--builders", options->builders, "binned, sweep, centroid, sbvh")
        ->check(CLI::IsMember({"binned", "sweep", "centroid", "sbvh"}))
        ->delimiter(',')
        ->capture_default_str();
    cpu->add_option("-o,--output", options->output, "Write the results as JSON here")
        ->check(WritableFile());
    cpu->callback([options, exitCode] {
        DropRepeats(&options->models);
        DropRepeats(&options->builders);
        CheckBenchModels(options->models, options->output);
        RunBench(*options);
        *exitCode = kExitOk;
    });
    auto ecsCount = std::make_shared<uint32_t>(1000000);
    CLI::App* ecsBench = bench->add_subcommand(
        "ecs", "Create, iterate and destroy entities in the entity-component system");
    ecsBench->add_option("--count", *ecsCount, "Entities")
        ->check(CLI::Range(1, 50000000))
        ->capture_default_str();
    ecsBench->callback([ecsCount, exitCode] {
        RunEcsBench(*ecsCount);
        *exitCode = kExitOk;
    });
    struct GridOptions {
        std::vector<uint32_t> counts{1000, 10000, 100000, 1000000};
        int frames = 200;
        std::string output;
    };
    auto grid = std::make_shared<GridOptions>();
    CLI::App* gridBench = bench->add_subcommand(
        "grid", "GPU: N moving dragon instances, TLAS rebuilt every frame (update, TLAS, trace)");
    gridBench->add_option("--counts", grid->counts, "Instance counts")
        ->delimiter(',')
        ->check(CLI::Range(1u, 10000000u))
        ->capture_default_str();
    gridBench->add_option("--frames", grid->frames, "Timed frames per count")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    gridBench->add_option("-o,--output", grid->output, "Write the results as JSON here")
        ->check(WritableFile());
    gridBench->callback([grid, exitCode] {
        std::string why;
        if (!CudaBackendAvailable(&why))
            throw InputError("bench grid", "", why + "; the instance grid is timed on a GPU only");
        RunGridBench(grid->counts, grid->frames, grid->output);
        *exitCode = kExitOk;
    });
    struct RuntimeOptions {
        std::vector<std::string> scenes;
        int frames = 300;
        std::vector<int> threads{0};
        std::vector<std::string> solvers{"cpu"};
    };
    auto runtime = std::make_shared<RuntimeOptions>();
    CLI::App* runtimeBench = bench->add_subcommand(
        "runtime", "CPU time per runtime stage (physics, animation, transforms, extraction, TLAS)");
    runtimeBench->add_option("scenes", runtime->scenes, "Scene files or names to play")->required();
    runtimeBench->add_option("--frames", runtime->frames, "Frames to play")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    runtimeBench
        ->add_option("--threads", runtime->threads,
                     "Thread counts to play each scene with, e.g. 1,4,16 (0: every core); a "
                     "world of fewer than 1,024 rigid bodies steps on one")
        ->delimiter(',')
        ->allow_extra_args(false)
        ->check(CLI::Range(0, 1024))
        ->capture_default_str();
    runtimeBench
        ->add_option("--physics-solver", runtime->solvers,
                     "Contact solvers to play each scene with: cpu, gpu or cpu,gpu")
        ->delimiter(',')
        ->allow_extra_args(false)
        ->check(CLI::IsMember({"cpu", "gpu"}))
        ->capture_default_str();
    runtimeBench->callback([runtime, exitCode] {
        for (const std::string& solver : runtime->solvers) CheckPhysicsSolver(solver);
        RunRuntimeBench(runtime->scenes, runtime->frames, runtime->threads, runtime->solvers);
        *exitCode = kExitOk;
    });
    AddFrameBench(*bench, exitCode);
    AddSplitBench(*bench, exitCode);
    AddDeformBench(*bench, exitCode);
    AddSoakBench(*bench, exitCode);
    AddAccuracyBench(*bench, exitCode);
    AddMaterialsBench(*bench, exitCode);
    AddEmbreeBench(*bench, exitCode);
    CLI::App* gpu = bench->add_subcommand(
        "gpu", "Trace time on the GPU (CUDA events) of the paper scene, median of --frames");
    gpu->add_option("--frames", options->gpuFrames,
                    "Timed frames per model after 20 warm-up frames")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    AddModelsOption(gpu, &options->models);
    gpu->add_option("--builders", options->gpuBuilders,
                    "BLAS builders to trace with, one after the other: binned, sweep, centroid, "
                    "sbvh")
        ->check(CLI::IsMember({"binned", "sweep", "centroid", "sbvh"}))
        ->delimiter(',')
        ->capture_default_str();
    gpu->add_option("-o,--output", options->output, "Write the results as JSON here")
        ->check(WritableFile());
    gpu->callback([options, exitCode] {
        std::string why;
        if (!CudaBackendAvailable(&why))
            throw InputError("bench gpu", "", why + "; rtrt bench cpu times the CPU back end");
        DropRepeats(&options->models);
        DropRepeats(&options->gpuBuilders);
        CheckBenchModels(options->models, options->output);
        RunGpuBench(*options);
        *exitCode = kExitOk;
    });
}

void WriteReportFile(const std::string& path, const std::string& text) {
    WriteWholeFile(path, text, /*durable=*/false);
}

void WriteReportIfNamed(const std::string& path, const nlohmann::json& report) {
    if (path.empty()) return;
    WriteReport(path, report);
    std::printf("rtrt: wrote %s\n", path.c_str());
}

nlohmann::json BenchMachine(bool gpu) {
    nlohmann::json m = MachineInfo();
    if (gpu)
        m["gpu"] = CommandOutput(
            "nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null");
    return m;
}

}  // namespace rtrt
