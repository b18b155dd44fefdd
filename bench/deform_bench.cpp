// `rtrt bench deform`: a deforming mesh played for --frames frames under three BLAS policies at
// once (refit every frame, rebuild every frame, the runtime's adaptive policy), each through its
// own frame renderer: the deform and BLAS stages' times and throughput, the whole frame, and the
// quality drift of the refit tree: at --samples poses, the trace time of the refit tree against a
// fresh SAH build and a fresh LBVH of the same triangles (traced alone, medians of 20 launches).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "bench/backend_option.h"
#include "bench/bench_commands.h"
#include "bench/bench_report.h"
#include "bench/gpu_trace_timing.h"
#include "engine/bvh/build/lbvh.h"
#include "engine/core/error.h"
#include "engine/core/output_file.h"
#include "engine/core/timer.h"
#include "engine/render_rt/cpu/cpu_deformer.h"
#include "engine/render_rt/frame_renderer.h"
#include "engine/render_rt/renderer.h"
#include "game/runtime/world.h"
#include "game/scene/scene_file.h"

namespace rtrt {
namespace {

struct DeformBenchOptions {
    std::string scene;
    std::string backend = "auto";
    std::string size;
    int frames = 600;
    int samples = 7;
    std::string output, csv;
};

struct PolicyRun {
    const char* name;
    BlasRebuildPolicy policy;
    std::unique_ptr<World> world;
    std::unique_ptr<FrameRenderer> renderer;
    std::vector<double> deform, blas, tlas, trace, frame;
    uint32_t rebuilds = 0;
};

BlasRebuildPolicy Mode(BlasRebuildPolicy::Mode mode) {
    BlasRebuildPolicy p;
    p.mode = mode;
    return p;
}

// The scene as the world has it, with deformation d's BLAS replaced by `blas`: traced alone.
double TraceMs(const RenderScene& played, uint32_t blasId, Blas blas,
               const RenderSettings& settings, bool gpu) {
    RenderScene still = played;
    still.deformations.clear();
    still.blases[blasId] = std::make_shared<const Blas>(std::move(blas));
    still.BuildTlas();
    if (gpu) return Median(TimeCudaTrace(still, settings, 5, 20));
    std::vector<double> ms;
    for (int i = 0; i < 3; ++i) {
        Stopwatch t;
        RenderRaw(still, settings);
        ms.push_back(t.Milliseconds());
    }
    return Median(ms);
}

Blas LbvhOf(const Blas& refit) {
    std::vector<Aabb> boxes;
    for (const Triangle& t : refit.triangles) boxes.push_back(t.Bounds());
    Lbvh tree = BuildLbvh(boxes);
    Blas blas;
    blas.nodes = std::move(tree.nodes);
    for (uint32_t slot = 0; slot < tree.primOrder.size(); ++slot)
        blas.triangles.push_back(refit.triangles[tree.primOrder[slot]]);
    blas.primIds.resize(blas.triangles.size());
    blas.bounds = blas.nodes[0].Bounds();
    return blas;
}

void RunDeformBench(const DeformBenchOptions& o) {
    const bool gpu = o.backend == "cuda";
    const LoadedScene loaded = LoadSceneFile(o.scene);
    RefuseOutputOverAsset(o.output);
    RefuseOutputOverAsset(o.csv);
    RenderSettings settings;
    settings.width = loaded.width.value_or(1280);  // as render and play
    settings.height = loaded.height.value_or(720);
    if (!o.size.empty()) ParseSize(o.size, &settings.width, &settings.height);
    settings.maxDepth = loaded.scene.maxDepth;
    const Backend backend = gpu ? Backend::kCuda : Backend::kCpu;
    PolicyRun runs[3] = {{"refit", Mode(BlasRebuildPolicy::Mode::kAlwaysRefit)},
                         {"rebuild", Mode(BlasRebuildPolicy::Mode::kAlwaysRebuild)},
                         {"adaptive", BlasRebuildPolicy{}}};
    for (PolicyRun& r : runs) {
        r.world = std::make_unique<World>(loaded);
        r.renderer = MakeFrameRenderer(backend, r.world->Scene(), {}, r.policy);
    }
    const RenderScene& scene0 = runs[0].world->Scene();
    if (scene0.deformations.empty())
        throw InputError(o.scene, "instances",
                         "no instance deforms at the start (give one a \"deform\" and no later "
                         "\"time\")");
    const uint32_t blasId = scene0.deformations[0].blasId;
    uint64_t triangles = 0;
    for (const Deformation& d : scene0.deformations)
        triangles += scene0.blases[d.blasId]->SourcePrimCount();
    // The refit tree again on the host, for the drift samples (the same steps as the device's).
    CpuDeformer refitOnHost(Mode(BlasRebuildPolicy::Mode::kAlwaysRefit));
    std::vector<BlasView> views(scene0.blases.size());
    std::vector<Aabb> bounds(scene0.blases.size());
    std::printf("rtrt bench deform (%s back end): %s, %llu deforming triangles, %ux%u, %d frames\n",
                o.backend.c_str(), std::filesystem::path(o.scene).filename().string().c_str(),
                (unsigned long long)triangles, settings.width, settings.height, o.frames);
    nlohmann::json drift = nlohmann::json::array();
    std::ostringstream csv;  // written whole at the end, as the JSON
    const bool writeCsv = !o.csv.empty();
    if (writeCsv) {
        csv << "frame";
        for (const PolicyRun& r : runs)
            csv << "," << r.name << "_deform_ms," << r.name << "_blas_ms," << r.name << "_trace_ms";
        csv << ",adaptive_rebuilt\n";
    }
    // --samples poses spread evenly from frame 0 to the last (fewer where there are fewer frames).
    std::vector<int> sampleFrames;
    for (int i = 0; i < o.samples; ++i) {
        const int f = int((int64_t(i) * o.frames + (o.samples - 1) / 2) / (o.samples - 1));
        if (sampleFrames.empty() || f != sampleFrames.back()) sampleFrames.push_back(f);
    }
    for (int f = 0; f <= o.frames; ++f) {
        if (writeCsv) csv << f;
        for (PolicyRun& r : runs) {
            Stopwatch frameTimer;
            if (f > 0) r.world->Advance(1.0f / 60.0f);
            r.renderer->Update(r.world->Scene(), r.world->Changes());
            r.renderer->Trace(r.world->Scene(), settings, nullptr);
            r.renderer->Finish();
            const double frameMs = frameTimer.Milliseconds();
            const FrameTimes& t = r.renderer->Times();
            if (f > 0) {  // frame 0 admits the deformation: its first update is not typical
                r.deform.push_back(t.deformMs);
                r.blas.push_back(t.blasMs);
                r.tlas.push_back(t.tlasMs);
                r.trace.push_back(t.traceMs);
                r.frame.push_back(frameMs);
                r.rebuilds += t.blasRebuilt;
            }
            if (writeCsv) csv << "," << t.deformMs << "," << t.blasMs << "," << t.traceMs;
        }
        if (writeCsv) csv << "," << runs[2].renderer->Times().blasRebuilt << "\n";
        const RenderScene& now = runs[0].world->Scene();
        std::vector<uint32_t> all(now.deformations.size());
        for (uint32_t d = 0; d < all.size(); ++d) all[d] = d;
        // The first update takes the deformations in (and deforms them) by itself. Each
        // deformation spawned since has added a BLAS.
        views.resize(now.blases.size());
        bounds.resize(now.blases.size());
        refitOnHost.Update(now,
                           f > 0 ? std::span<const uint32_t>(all) : std::span<const uint32_t>(),
                           views, bounds);
        if (!std::binary_search(sampleFrames.begin(), sampleFrames.end(), f)) continue;
        const Blas refit = refitOnHost.Snapshot(0);
        const double refitMs = TraceMs(now, blasId, refit, settings, gpu);
        TriangleMesh triangles = RestMeshOfBlas(refit).rest;
        triangles.normals.clear();  // flat, as the drift results in bench/results were measured
        Blas sah = BuildTriangleBlas(triangles);
        sah.nodes4.clear();  // the CPU traces refit trees in the binary layout: so this one too
        const double sahMs = TraceMs(now, blasId, std::move(sah), settings, gpu);
        const double lbvhMs = TraceMs(now, blasId, LbvhOf(refit), settings, gpu);
        std::printf(
            "  frame %4d: trace of the refit tree %.3f ms, fresh SAH %.3f ms (x%.3f), "
            "fresh LBVH %.3f ms (x%.3f)\n",
            f, refitMs, sahMs, refitMs / sahMs, lbvhMs, refitMs / lbvhMs);
        std::fflush(stdout);
        drift.push_back({{"frame", f},
                         {"refit_trace_ms", refitMs},
                         {"fresh_sah_trace_ms", sahMs},
                         {"fresh_lbvh_trace_ms", lbvhMs}});
    }
    nlohmann::json report;
    report["machine"] = BenchMachine(gpu);
    report["backend"] = o.backend;
    report["scene"] = std::filesystem::path(o.scene).filename().string();
    report["width"] = settings.width;
    report["height"] = settings.height;
    report["frames"] = o.frames;
    report["deforming_triangles"] = triangles;
    report["timing"] =
        "medians over the frames after the first; GPU stages by CUDA events, the frame by the CPU "
        "clock from update to finished image; drift samples trace the tree alone (20 launches)";
    std::printf("%-9s %9s %9s %9s %9s %9s %9s %14s\n", "policy", "deform", "BLAS", "TLAS", "trace",
                "frame", "rebuilds", "BLAS Mtri/ms");
    for (const PolicyRun& r : runs) {
        const double blasMs = Median(r.blas);
        const double throughput = blasMs > 0.0 ? double(triangles) * 1e-6 / blasMs : 0.0;
        std::printf("%-9s %9.3f %9.3f %9.3f %9.3f %9.3f %9u %14.2f\n", r.name, Median(r.deform),
                    blasMs, Median(r.tlas), Median(r.trace), Median(r.frame), r.rebuilds,
                    throughput);
        report["policies"].push_back(
            {{"policy", r.name},
             {"deform_ms", Median(r.deform)},
             {"blas_ms", blasMs},
             {"tlas_ms", Median(r.tlas)},
             {"trace_ms", Median(r.trace)},
             {"frame_ms", Median(r.frame)},
             {"rebuilds", r.rebuilds},
             {"blas_mtri_per_ms", throughput},
             {"deform_mtri_per_ms", double(triangles) * 1e-6 / Median(r.deform)}});
    }
    report["drift"] = drift;
    // Both outputs are finished before either takes its name, so that a failure of either
    // leaves neither.
    std::vector<std::pair<std::string, std::string>> outputs;
    if (!o.output.empty()) outputs.emplace_back(o.output, report.dump(2) + "\n");
    if (writeCsv) outputs.emplace_back(o.csv, csv.str());
    std::vector<std::unique_ptr<OutputFile>> files;
    for (const auto& [path, text] : outputs) {
        files.push_back(std::make_unique<OutputFile>(path));
        files.back()->Write(text.data(), text.size());
        files.back()->Finish(/*durable=*/false);
    }
    for (size_t k = 0; k < files.size(); ++k) {
        files[k]->Commit();
        std::printf("rtrt: wrote %s\n", outputs[k].first.c_str());
    }
}

}  // namespace

void AddDeformBench(CLI::App& bench, int* exitCode) {
    auto o = std::make_shared<DeformBenchOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "deform",
        "A deforming mesh under refit, rebuild and adaptive BLAS policies, and the "
        "refit tree's quality drift");
    cmd->add_option("scene", o->scene, "Scene file or name with a deforming instance")->required();
    AddBackendOption(cmd, &o->backend);
    cmd->add_option("--size", o->size, "WIDTHxHEIGHT (default: the scene's image size)");
    cmd->add_option("--frames", o->frames, "Frames to play at 60 fps")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    cmd->add_option("--samples", o->samples,
                    "Poses at which the drift is measured, from frame 0 to the last (at most one "
                    "a frame)")
        ->check(CLI::Range(2, 1000))
        ->capture_default_str();
    cmd->add_option("-o,--output", o->output, "Write the results as JSON here")
        ->check(WritableFile());
    cmd->add_option("--csv", o->csv, "Write every frame's stage times as CSV here")
        ->check(WritableFile());
    cmd->callback([o, exitCode] {
        ResolveBackendOption(&o->backend);
        RunDeformBench(*o);
        *exitCode = kExitOk;
    });
}

}  // namespace rtrt
