#include <cstdio>
#include <string>

#include "engine/core/error.h"
#include "engine/core/output_file.h"
#include "engine/core/timer.h"
#include "engine/render_rt/frame_renderer.h"
#include "engine/render_rt/renderer.h"
#include "game/assets/image_io.h"
#include "game/cli/cli_options.h"
#include "game/cli/commands.h"
#include "game/runtime/world.h"
#include "game/scene/default_scene.h"
#include "game/scene/scene_file.h"

namespace rtrt {
namespace {

struct RenderOptions {
    std::string scene = "default";
    std::string output;
    std::string size;
    std::string backend = "cpu";
    std::string gpus = "1";
    std::string view = "shaded";
    int maxDepth = 0;  // 0: the scene's own
    uint32_t spp = 1;
    std::string traversal = "auto";
    OutputOptions display;  // exposure and tone map
};

}  // namespace

namespace {

ViewMode ParseView(const std::string& view) {
    if (view == "normals") return ViewMode::kNormals;
    if (view == "depth") return ViewMode::kDepth;
    if (view == "heatmap") return ViewMode::kHeatmap;
    return ViewMode::kShaded;
}

bool HasDeformation(const LoadedScene& loaded) {
    for (const EntityDesc& e : loaded.entities)
        if (e.deformableMesh >= 0 && e.spawnTime <= 0.0f) return true;
    return false;
}

void RunRender(const RenderOptions& o) {
    CheckImagePath(o.output);
    RenderSettings settings;
    LoadedScene loaded;
    Stopwatch loadTimer;
    if (o.scene == "default")
        loaded.scene = MakeDefaultScene();
    else
        loaded = LoadSceneFile(o.scene);
    RefuseOutputOverAsset(o.output);
    const double loadMs = loadTimer.Milliseconds();
    settings.width = loaded.width.value_or(1280);
    settings.height = loaded.height.value_or(720);
    if (!o.size.empty()) ParseSize(o.size, &settings.width, &settings.height);
    CheckImageSize(o.output, settings.width, settings.height);
    settings.maxDepth = o.maxDepth > 0 ? uint32_t(o.maxDepth) : loaded.scene.maxDepth;
    settings.view = ParseView(o.view);
    settings.samplesPerPixel = o.spp;
    ParseTraversalForm(o.traversal, &settings.traversal);  // checked by the option
    const Backend backend = o.backend == "cuda" ? Backend::kCuda : Backend::kCpu;
    std::string why;
    if (backend == Backend::kCuda && !CudaBackendAvailable(&why))
        throw InputError("--backend", "cuda", why + "; use --backend cpu");
    const GpuSplit gpus = ResolveGpus(o.gpus, backend);
    CheckTraversalBackend(o.traversal, backend);
    // Only the shaded view is radiance; normals, depth and heatmaps are display values.
    const OutputTransform transform = settings.view == ViewMode::kShaded
                                          ? ResolveOutput(loaded.output, o.display)
                                          : kDisplayValues;

    Stopwatch renderTimer;
    RenderStats stats;
    Image raw;
    if (HasDeformation(loaded)) {
        // Deformed meshes exist only in a running scene: its first frame is the image.
        World world(loaded);
        auto renderer = MakeFrameRenderer(backend, world.Scene(), {}, {}, gpus);
        renderer->Update(world.Scene(), world.Changes());
        renderer->Trace(world.Scene(), settings, &raw, &stats);
    } else if (!gpus.devices.empty()) {  // the frame split over the GPUs
        auto renderer = MakeFrameRenderer(backend, loaded.scene, {}, {}, gpus);
        renderer->Trace(loaded.scene, settings, &raw, &stats);
    } else {
        raw = backend == Backend::kCuda ? RenderRawCuda(loaded.scene, settings, &stats)
                                        : RenderRaw(loaded.scene, settings, &stats);
    }
    const double renderMs = renderTimer.Milliseconds();
    HeatmapScale heat;
    WriteImage(o.output, FinishView(raw, settings.view, &heat), transform);
    std::printf(
        "rtrt: wrote %s (%ux%u, %s back end, %s view): scene %.1f ms, render %.1f ms, %.2f M "
        "rays\n",
        o.output.c_str(), settings.width, settings.height, o.backend.c_str(), o.view.c_str(),
        loadMs, renderMs, double(stats.rays) * 1e-6);
    if (settings.view == ViewMode::kHeatmap)
        std::printf(
            "rtrt: heatmap scale: 0 to %.0f traversal steps (nodes visited + primitives tested) "
            "per primary ray\n",
            heat.maxSteps);
}

}  // namespace

void AddRenderCommand(CLI::App& app, int* exitCode) {
    auto options = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand(
        "render", "Render a scene file (or the built-in default scene) to an image");
    cmd->add_option("scene", options->scene,
                    "Scene file (.json, .gltf, .glb), the name of one of rtrt's own scenes (e.g. "
                    "dragon), or \"default\" for the built-in scene")
        ->capture_default_str();
    cmd->add_option("-o,--output", options->output, "Output image (.png, .exr, ...)")->required();
    cmd->add_option("--size", options->size,
                    "Image size WIDTHxHEIGHT (default: the scene's, else 1280x720)");
    cmd->add_option("--backend", options->backend, "cpu or cuda")
        ->check(CLI::IsMember({"cpu", "cuda"}))
        ->capture_default_str();
    cmd->add_option("--max-depth", options->maxDepth,
                    "Rays per path: 1 = primary only (default: the scene's)")
        ->check(CLI::Range(1, 16));
    cmd->add_option("--spp", options->spp,
                    "Samples per pixel of the shaded view, n x n stratified (1, 4, 9, 16...)")
        ->check(CLI::IsMember({1u, 4u, 9u, 16u, 25u, 36u, 49u, 64u}))
        ->capture_default_str();
    cmd->add_option("--view", options->view, "shaded, normals, depth or heatmap")
        ->check(CLI::IsMember({"shaded", "normals", "depth", "heatmap"}))
        ->capture_default_str();
    AddGpusOption(cmd, &options->gpus);
    AddTraversalOption(cmd, &options->traversal);
    AddOutputOptions(cmd, &options->display);
    cmd->callback([options, exitCode] {
        RunRender(*options);
        *exitCode = kExitOk;
    });
}

}  // namespace rtrt
