// `rtrt bench embree`: the paper scene's CPU frame traced through rtrt's BVH and through Embree 3
// in one process, as interleaved pairs. Both frames run the same loop (trace_tiles.h): the same
// camera, shading and secondary rays, only the scene queries differ (EmbreePolicy), so the ratio
// is that of the two traversals inside a whole frame.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_commands.h"
#include "bench/bench_report.h"
#include "bench/embree/embree_policy.h"
#include "bench/embree/embree_scene.h"
#include "engine/core/error.h"
#include "engine/core/timer.h"
#include "engine/render_rt/cpu/trace_tiles.h"
#include "engine/render_rt/render_settings.h"
#include "game/assets/image_io.h"
#include "game/scene/paper_scene.h"

namespace rtrt {
namespace {

// What the paper scene calls for (checked per model): the one specialisation both frames use,
// the one `rtrt render --backend cpu` runs for it.
constexpr uint32_t kPaperFeatures = kFeatureShadows | kFeatureReflection;

struct EmbreeBenchOptions {
    int pairs = 7;
    std::vector<std::string> models{"dragon"};
    std::string output;
};

template <class Policy>
double TimeFrame(const RenderSceneView& view, Image& image, uint64_t* rays) {
    Stopwatch timer;
    *rays = TraceTiles<kPaperFeatures, Policy>(view, ViewMode::kShaded, image);
    return timer.Milliseconds();
}

// Pixels whose 8-bit display values differ between the two frames (the triangle tests differ in
// their last bits, so a few pixels on edges and in highlights round differently), and the largest
// difference in levels.
struct FrameDifference {
    size_t pixels = 0;
    int maxLevels = 0;
};
FrameDifference Compare(const Image& a, const Image& b) {
    const std::vector<uint8_t> x = EightBit(a), y = EightBit(b);
    FrameDifference d;
    for (size_t i = 0; i < x.size(); i += 3) {
        int m = 0;
        for (size_t c = 0; c < 3; ++c) m = std::max(m, std::abs(int(x[i + c]) - int(y[i + c])));
        d.pixels += m > 0;
        d.maxLevels = std::max(d.maxLevels, m);
    }
    return d;
}

void RunEmbreeBench(const EmbreeBenchOptions& o) {
    nlohmann::json report;
    report["machine"] = BenchMachine(false);
    report["scene"] = "paper scene, 1920x1080, max depth 2, one ray per pixel centre";
    report["method"] =
        "both frames through trace_tiles.h; rtrt's traversal against Embree 3's rtcIntersect1 and "
        "rtcOccluded1 (high-quality build); pairs interleaved, first of each pair alternating";
    std::printf("rtrt bench embree: %s, %u threads, Embree %s\n",
                report["machine"]["cpu"].get<std::string>().c_str(),
                std::thread::hardware_concurrency(), RTC_VERSION_STRING);
    std::printf("%-12s %10s %9s | %10s %10s %10s | %8s %9s %9s\n", "model", "triangles", "build ms",
                "rtrt ms", "embree ms", "rtrt/emb", "M rays", "diff px", "max lvl");
    for (const BenchModel& model : LoadBenchModels(o.models)) {
        const std::string& name = model.name;
        if (!model.mesh) {
            SkipMissingModel(report, name);
            continue;
        }
        const TriangleMesh& mesh = *model.mesh;
        const RenderScene scene =
            MakePaperScene(std::make_shared<const Blas>(BuildTriangleBlas(mesh)));
        const RenderSettings settings{kPaperWidth, kPaperHeight, kPaperMaxDepth};
        const uint32_t features =
            EffectiveFeatures(scene.Features(), settings.enabledFeatures, ViewMode::kShaded);
        if (features != kPaperFeatures)
            throw std::logic_error(
                "bench embree: the paper scene no longer calls for shadows "
                "and reflection alone; update kPaperFeatures");
        const EmbreeScene embree(scene);
        EmbreePolicy::scene = embree.Handle();
        RenderSceneView view = scene.HostView(settings.width, settings.height, settings.maxDepth);
        view.samplesPerPixel = settings.samplesPerPixel;
        Image ours(view.width, view.height), theirs(view.width, view.height);
        uint64_t oursRays = 0, theirRays = 0;
        TimeFrame<TracePolicy>(view, ours, &oursRays);  // warm-up
        TimeFrame<EmbreePolicy>(view, theirs, &theirRays);
        std::vector<double> oursMs, theirMs, ratios;
        for (int i = 0; i < o.pairs; ++i) {
            double a, b;
            if (i % 2 == 0) {
                a = TimeFrame<TracePolicy>(view, ours, &oursRays);
                b = TimeFrame<EmbreePolicy>(view, theirs, &theirRays);
            } else {
                b = TimeFrame<EmbreePolicy>(view, theirs, &theirRays);
                a = TimeFrame<TracePolicy>(view, ours, &oursRays);
            }
            oursMs.push_back(a);
            theirMs.push_back(b);
            ratios.push_back(a / b);
        }
        EmbreePolicy::scene = nullptr;
        const FrameDifference diff = Compare(ours, theirs);
        const double ratio = Median(ratios);
        std::printf("%-12s %10zu %9.1f | %10.1f %10.1f %10.3f | %8.2f %9zu %9d\n", name.c_str(),
                    mesh.indices.size(), embree.BuildMs(), Median(oursMs), Median(theirMs), ratio,
                    double(oursRays) * 1e-6, diff.pixels, diff.maxLevels);
        report["models"].push_back({{"model", name},
                                    {"triangles", mesh.indices.size()},
                                    {"embree_build_ms", embree.BuildMs()},
                                    {"rtrt_frame_ms", oursMs},
                                    {"embree_frame_ms", theirMs},
                                    {"rtrt_frame_ms_median", Median(oursMs)},
                                    {"embree_frame_ms_median", Median(theirMs)},
                                    {"ratio_median_of_pairs", ratio},
                                    {"rtrt_rays", oursRays},
                                    {"embree_rays", theirRays},
                                    {"differing_8bit_pixels", diff.pixels},
                                    {"max_8bit_difference", diff.maxLevels}});
    }
    WriteReportIfNamed(o.output, report);
}

}  // namespace

void AddEmbreeBench(CLI::App& bench, int* exitCode) {
    auto options = std::make_shared<EmbreeBenchOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "embree",
        "CPU frame of the paper scene through rtrt's BVH and through Embree 3, as "
        "interleaved pairs");
    cmd->add_option("--pairs", options->pairs, "Timed pairs per model (medians reported)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    AddModelsOption(cmd, &options->models)->capture_default_str();
    cmd->add_option("-o,--output", options->output, "Write the results as JSON here")
        ->check(WritableFile());
    cmd->callback([options, exitCode] {
        DropRepeats(&options->models);
        CheckBenchModels(options->models, options->output);
        RunEmbreeBench(*options);
        *exitCode = kExitOk;
    });
}

}  // namespace rtrt
