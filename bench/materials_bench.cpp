// `rtrt bench materials`: what glTF's PBR shading and its textures cost on the GPU. The same
// scene's trace (CUDA events) with PBR kernels, with their Blinn-Phong approximation (the same
// textures, kFeaturePbr off) and untextured Blinn-Phong (kFeatureTextures off too): the scene,
// rays and traversal are the same, only the shading differs.
#include <algorithm>
#include <cstdio>
#include <filesystem>
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

struct MaterialsBenchOptions {
    std::vector<std::string> scenes;
    std::string backend = "cuda";
    std::string size = "1920x1080";
    int frames = 200;
    int warmup = 20;
    std::string output;
};

struct ShadingVariant {
    const char* name;
    uint32_t enabledFeatures;
};
constexpr ShadingVariant kVariants[] = {
    {"pbr", kAllFeatures},
    {"blinn_phong_textured", kAllFeatures & ~kFeaturePbr},
    {"blinn_phong_untextured", kAllFeatures & ~kFeaturePbr & ~kFeatureTextures},
};

nlohmann::json RunScene(const std::string& path, const LoadedScene& loaded,
                        const MaterialsBenchOptions& o) {
    RenderSettings settings;
    ParseSize(o.size, &settings.width, &settings.height);
    settings.maxDepth = loaded.scene.maxDepth;
    World world(loaded);
    world.Advance(1.0f / 60.0f);
    const std::unique_ptr<FrameRenderer> renderer =
        MakeFrameRenderer(o.backend == "cuda" ? Backend::kCuda : Backend::kCpu, world.Scene());
    renderer->Update(world.Scene(), world.Changes());
    nlohmann::json row = {{"scene", std::filesystem::path(path).filename().string()},
                          {"width", settings.width},
                          {"height", settings.height},
                          {"scene_features", world.Scene().Features()}};
    double pbrMs = 0.0;
    for (const ShadingVariant& v : kVariants) {
        settings.enabledFeatures = v.enabledFeatures;
        std::vector<double> trace;
        RenderStats stats;
        uint64_t rays = 0;
        for (int f = 0; f < o.warmup + o.frames; ++f) {
            renderer->Trace(world.Scene(), settings, nullptr, f == 0 ? &stats : nullptr);
            renderer->Finish();
            if (f == 0) rays = std::max<uint64_t>(stats.rays, renderer->Times().rays);
            if (f >= o.warmup) trace.push_back(renderer->Times().traceMs);
        }
        const double ms = Median(trace);
        if (pbrMs == 0.0) pbrMs = ms;
        row[v.name] = {{"trace_ms", ms}, {"rays", rays}};
        std::printf("%-24s %-24s %9.3f %9.2f %12llu\n", row["scene"].get<std::string>().c_str(),
                    v.name, ms, ms / pbrMs, (unsigned long long)rays);
    }
    return row;
}

}  // namespace

void AddMaterialsBench(CLI::App& bench, int* exitCode) {
    auto o = std::make_shared<MaterialsBenchOptions>();
    CLI::App* cmd =
        bench.add_subcommand("materials",
                             "Trace time with PBR shading against its Blinn-Phong approximation, "
                             "textured and untextured (median of --frames)");
    cmd->add_option("scenes", o->scenes,
                    "Scene or glTF files (e.g. assets/models/pbr_showcase.gltf), or scene names")
        ->required();
    AddBackendOption(cmd, &o->backend, false);
    cmd->add_option("--size", o->size, "WIDTHxHEIGHT")->capture_default_str();
    cmd->add_option("--frames", o->frames, "Timed frames per variant")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    cmd->add_option("--warmup", o->warmup, "Untimed frames first")
        ->check(CLI::Range(0, 100000))
        ->capture_default_str();
    cmd->add_option("-o,--output", o->output, "Write the results as JSON here")
        ->check(WritableFile());
    cmd->callback([o, exitCode] {
        ResolveBackendOption(&o->backend);
        // The size and every scene are read before any is measured: a bad one had failed the
        // command after the scenes before it were measured.
        uint32_t width = 0, height = 0;
        ParseSize(o->size, &width, &height);
        std::vector<LoadedScene> loaded;
        loaded.reserve(o->scenes.size());
        for (const std::string& path : o->scenes) loaded.push_back(LoadSceneFile(path));
        RefuseOutputOverAsset(o->output);
        nlohmann::json report;
        report["machine"] = BenchMachine(o->backend == "cuda");
        report["backend"] = o->backend;
        report["timing"] =
            "trace only, medians over --frames frames after --warmup frames, CUDA "
            "events on the GPU; the scene's first frame, unchanged";
        std::printf("rtrt bench materials (%s back end, %s), medians over %d frames\n",
                    o->backend.c_str(), o->size.c_str(), o->frames);
        std::printf("%-24s %-24s %9s %9s %12s\n", "scene", "shading", "trace ms", "x pbr", "rays");
        for (size_t i = 0; i < o->scenes.size(); ++i)
            report["rows"].push_back(RunScene(o->scenes[i], loaded[i], *o));
        WriteReportIfNamed(o->output, report);
        *exitCode = kExitOk;
    });
}

}  // namespace rtrt
