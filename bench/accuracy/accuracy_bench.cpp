// `rtrt bench accuracy`: the knobs that trade accuracy for time, one at a time away from a base
// setting, each timed on the CPU and/or the GPU and compared with the double-precision reference
// (docs/accuracy.md defines the scenes, settings and measures).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench/accuracy/accuracy_policy.h"
#include "bench/accuracy/accuracy_renderer.h"
#include "bench/accuracy/accuracy_scenes.h"
#include "bench/accuracy/image_metrics.h"
#include "bench/bench_commands.h"
#include "bench/bench_report.h"
#include "engine/core/error.h"
#include "engine/core/output_file.h"
#include "engine/core/timer.h"
#include "game/assets/image_io.h"
#include "game/assets/mesh_io.h"
#include "game/assets/model_dir.h"
#include "game/assets/procedural_shapes.h"

namespace rtrt {
namespace {

struct AccuracyOptions {
    std::string size;
    std::string backend = "cpu";
    int cpuFrames = 5;
    int gpuWarmup = 5;
    int gpuFrames = 20;
    std::string output;
    std::string images;
};

// One row: the base setting with one knob changed.
struct Setting {
    std::string name;
    std::string knob;
    std::string scene;  // "dragon" or "spheres"
    uint32_t accuracy = kAccuracyDefault;
    uint32_t spp = 16;
    uint32_t depth = 8;
    BvhBuilder builder = BvhBuilder::kBinnedSah;
    bool reference = false;  // double precision, CPU only
    int lbvhFrames = -1;     // UseRuntimeTlas(frames); -1: the SAH TLAS built for the scene
};

// Colour outliers: a channel off by more than this (acne, leaks, missing objects).
constexpr float kOutlierThreshold = 0.1f;

std::vector<Setting> Settings() {
    std::vector<Setting> s;
    s.push_back(
        {"reference: double", "precision", "dragon", 0, 16, 8, BvhBuilder::kSweepSah, true});
    s.push_back({"base: float", "precision", "dragon"});
    for (uint32_t depth : {1u, 2u, 3u, 4u}) {
        Setting d{"max depth " + std::to_string(depth), "max depth", "dragon"};
        d.depth = depth;
        s.push_back(d);
    }
    for (uint32_t spp : {1u, 4u, 9u}) {
        Setting d{std::to_string(spp) + " spp", "samples per pixel", "dragon"};
        d.spp = spp;
        s.push_back(d);
    }
    s.push_back({"Moller-Trumbore", "triangle test", "dragon", kAccuracyMollerTrumbore});
    s.push_back({"fixed epsilon 1e-4", "ray offset", "dragon", kAccuracyFixedEpsilon});
    s.push_back({"Moller-Trumbore + fixed epsilon", "ray offset", "dragon",
                 kAccuracyMollerTrumbore | kAccuracyFixedEpsilon});
    s.push_back({"naive quadratic", "sphere test", "dragon", kAccuracyNaiveSphere});
    s.push_back({"float only (no double near hits)", "near hits", "dragon", kAccuracyFloatOnly});
    Setting sweep{"sweep SAH", "BLAS builder", "dragon"};
    sweep.builder = BvhBuilder::kSweepSah;
    s.push_back(sweep);
    Setting centroid{"centroid split", "BLAS builder", "dragon"};
    centroid.builder = BvhBuilder::kCentroidSplit;
    s.push_back(centroid);
    Setting textbook{"textbook: MT + epsilon + naive, 1 spp, depth 4", "all", "dragon",
                     kTextbookAccuracy};
    textbook.spp = 1;
    textbook.depth = 4;
    s.push_back(textbook);
    s.push_back(
        {"reference: double", "precision", "spheres", 0, 16, 8, BvhBuilder::kSweepSah, true});
    s.push_back({"base: float", "precision", "spheres"});
    s.push_back({"naive quadratic", "sphere test", "spheres", kAccuracyNaiveSphere});
    s.push_back({"fixed epsilon 1e-4", "ray offset", "spheres", kAccuracyFixedEpsilon});
    s.push_back({"float only (no double near hits)", "near hits", "spheres", kAccuracyFloatOnly});
    for (int frames : {0, 10, 100, 1000}) {
        Setting lbvh{frames == 0 ? "LBVH rebuilt"
                                 : "LBVH refit " + std::to_string(frames) + " frames after build",
                     "TLAS update", "spheres"};
        lbvh.lbvhFrames = frames;
        s.push_back(lbvh);
    }
    return s;
}

std::string AccuracyName(uint32_t bits) {
    std::string name;
    name += (bits & kAccuracyMollerTrumbore) ? "moller-trumbore" : "watertight";
    name += (bits & kAccuracyFixedEpsilon) ? ", fixed epsilon" : ", error bounds";
    name += (bits & kAccuracyNaiveSphere) ? ", naive sphere" : ", rtg sphere";
    name += (bits & kAccuracyFloatOnly) ? ", float only" : ", double near hits";
    return name;
}

// The full dragon's file; InputError when it has not been fetched.
std::string DragonPath() {
    const std::string path = ModelDir() + "/dragon_vrip.ply.gz";
    if (!std::filesystem::exists(path))
        throw InputError(path, "", "missing; run rtrt fetch-models");
    return path;
}

TriangleMesh LoadDragon() {
    TriangleMesh mesh = LoadMesh(DragonPath());
    FitMesh(mesh, 5.0f);
    return mesh;
}

// The scenes, built once per (scene, builder).
class SceneSet {
  public:
    const RenderScene& Get(const std::string& name, BvhBuilder builder, int lbvhFrames) {
        const std::string key =
            name + "/" + std::string(BuilderName(builder)) + "/" + std::to_string(lbvhFrames);
        auto it = scenes_.find(key);
        if (it != scenes_.end()) return it->second;
        if (lbvhFrames >= 0) {
            RenderScene scene = Get(name, builder, -1);
            UseRuntimeTlas(scene, uint32_t(lbvhFrames));
            return scenes_.emplace(key, std::move(scene)).first->second;
        }
        if (name == "spheres") return scenes_.emplace(key, MakeFarSpheresScene()).first->second;
        if (dragonMesh_.indices.empty()) dragonMesh_ = LoadDragon();
        BvhBuildOptions options;
        options.builder = builder;
        auto blas = std::make_shared<const Blas>(BuildTriangleBlas(dragonMesh_, options));
        return scenes_.emplace(key, MakeAccuracyDragonScene(blas)).first->second;
    }

  private:
    TriangleMesh dragonMesh_;
    std::map<std::string, RenderScene> scenes_;
};

struct Reference {
    Image image;
    ObjectIds objects;
};

nlohmann::json Errors(const Image& image, const ObjectIds& objects, const Reference& ref) {
    const double rmse = Rmse(image, ref.image);
    const double psnr = Psnr(rmse);
    return {{"rmse", rmse},
            {"psnr_db", std::isinf(psnr) ? nlohmann::json(nullptr) : nlohmann::json(psnr)},
            {"outlier_rate", OutlierRate(image, ref.image, kOutlierThreshold)},
            {"mismatch_rate", MismatchRate(objects, ref.objects)}};
}

std::string ImageExtension() { return CanReadImages() ? ".png" : ".ppm"; }

std::string FileStem(const Setting& s, const char* backend) {
    std::string stem = s.scene + "_" + backend + "_";
    for (char c : s.name) stem += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return stem;
}

// Differences scaled by 4 so that rounding noise stays dark and acne stands out.
void WriteDifference(const std::string& dir, const std::string& stem, const Image& image,
                     const Image& reference) {
    Image diff = DifferenceImage(image, reference);
    for (vec3& p : diff.pixels) p = glm::min(4.0f * p, vec3(1.0f));
    WriteImage(dir + "/" + stem + ImageExtension(), diff);
}

void PrintRow(const Setting& s, const char* backend, double ms, uint64_t rays,
              const nlohmann::json& e) {
    const double psnr = e["psnr_db"].is_null() ? HUGE_VAL : e["psnr_db"].get<double>();
    std::printf("%-8s %-18s %-46s %-4s %10.1f %8.2f %9.5f %7.2f %9.3f %9.3f\n", s.scene.c_str(),
                s.knob.c_str(), s.name.c_str(), backend, ms, double(rays) * 1e-6,
                e["rmse"].get<double>(), psnr, 100.0 * e["outlier_rate"].get<double>(),
                100.0 * e["mismatch_rate"].get<double>());
    std::fflush(stdout);
}

void RunAccuracyBench(const AccuracyOptions& o) {
    const bool cpu = o.backend != "cuda", gpu = o.backend != "cpu";
    RenderSettings size;
    size.width = gpu && !cpu ? 1280 : 480;
    size.height = gpu && !cpu ? 720 : 270;
    if (!o.size.empty()) ParseSize(o.size, &size.width, &size.height);
    if (!o.images.empty()) {
        // Nothing is made before the input is known to be there (an empty folder was left), and
        // the report does not go where the images go (it had replaced dragon_reference.png).
        DragonPath();
        namespace fs = std::filesystem;
        std::error_code ec;
        if (!o.output.empty() && fs::weakly_canonical(fs::absolute(o.output).parent_path(), ec) ==
                                     fs::weakly_canonical(fs::absolute(o.images), ec))
            throw InputError("-o", o.output,
                             "is in the --images folder, where the bench writes its images: "
                             "give the report another folder");
        CreateOutputFolder(o.images);
    }
    nlohmann::json report;
    report["machine"] = BenchMachine(gpu);
    report["backend"] = o.backend;
    report["size"] = std::to_string(size.width) + "x" + std::to_string(size.height);
    report["timing"] = {
        {"cpu",
         "wall clock of the whole frame, 1 warm-up, median of " + std::to_string(o.cpuFrames)},
        {"gpu", "CUDA events around the trace kernel, " + std::to_string(o.gpuWarmup) +
                    " warm-up, median of " + std::to_string(o.gpuFrames)}};
    report["outlier_threshold"] = kOutlierThreshold;
    report["scenes"] = {
        {"dragon",
         "paper scene (full dragon, extent 5) + ground of 2 triangles, corners 1e5 away, "
         "y = y0 + 0.05 x - 0.1 z with y0 0.01 below the dragon + glass sphere r 1.2 at "
         "x 3.6, z 1.5 on the ground (transmissivity 0.95, ior 1.5)"},
        {"spheres",
         "7 x 4 instances of a sphere r 1.5 on a 4-unit grid at z = -4000, camera at the "
         "origin looking down -z, vertical FOV 0.3 degrees, light toward (1,1,1)"}};
    report["base"] =
        "float, watertight, error-bound offsets, RTG ch. 7 spheres, 16 spp, max "
        "depth 8, binned SAH BLAS, SAH TLAS";
    report["reference"] = "the base setting in double precision (CPU), sweep SAH BLAS";
    std::printf("rtrt bench accuracy: %s, %ux%u, %s\n",
                report["machine"]["cpu"].get<std::string>().c_str(), size.width, size.height,
                o.backend.c_str());
    std::printf("%-8s %-18s %-46s %-4s %10s %8s %9s %7s %9s %9s\n", "scene", "knob", "setting",
                "on", "ms", "M rays", "RMSE", "PSNR", "outlier%", "mismatch%");
    SceneSet scenes;
    std::map<std::string, Reference> references;
    for (const Setting& s : Settings()) {
        const RenderScene& scene = scenes.Get(s.scene, s.builder, s.lbvhFrames);
        RenderSettings settings = size;
        settings.samplesPerPixel = s.spp;
        settings.maxDepth = s.depth;
        nlohmann::json row = {{"name", s.name},
                              {"knob", s.knob},
                              {"scene", s.scene},
                              {"spp", s.spp},
                              {"max_depth", s.depth},
                              {"builder", BuilderName(s.builder)},
                              {"tlas", s.lbvhFrames < 0 ? "SAH" : "LBVH"},
                              {"tlas_frames_since_build", std::max(s.lbvhFrames, 0)},
                              {"precision", s.reference ? "double" : "float"},
                              {"tests", AccuracyName(s.accuracy)}};
        if (s.reference) {
            Stopwatch t;
            Reference ref{RenderReference(scene, settings), {}};
            const double ms = t.Milliseconds();
            ref.objects = ReferencePrimaryObjects(scene, settings);
            row["cpu"] = Errors(ref.image, ref.objects, ref);
            row["cpu"]["ms"] = ms;
            PrintRow(s, "cpu", ms, 0, row["cpu"]);
            if (!o.images.empty())
                WriteImage(o.images + "/" + s.scene + "_reference" + ImageExtension(), ref.image);
            references[s.scene] = std::move(ref);
            report["rows"].push_back(row);
            continue;
        }
        const Reference& ref = references.at(s.scene);
        if (cpu) {
            Image image;
            RenderStats stats;
            RenderAccuracyCpu(scene, settings, s.accuracy, image, &stats);  // warm-up
            std::vector<double> times;
            for (int i = 0; i < o.cpuFrames; ++i) {
                Stopwatch t;
                RenderAccuracyCpu(scene, settings, s.accuracy, image, &stats);
                times.push_back(t.Milliseconds());
            }
            row["cpu"] = Errors(image, PrimaryObjectsCpu(scene, settings, s.accuracy), ref);
            row["cpu"]["ms"] = Median(times);
            row["cpu"]["rays"] = stats.rays;
            PrintRow(s, "cpu", Median(times), stats.rays, row["cpu"]);
            if (!o.images.empty()) WriteDifference(o.images, FileStem(s, "cpu"), image, ref.image);
        }
        if (gpu) {
            const CudaAccuracyRun run =
                RunAccuracyCuda(scene, settings, s.accuracy, o.gpuWarmup, o.gpuFrames);
            row["gpu"] = Errors(run.image, run.objects, ref);
            row["gpu"]["ms"] = Median(run.traceMs);
            row["gpu"]["rays"] = run.rays;
            PrintRow(s, "gpu", Median(run.traceMs), run.rays, row["gpu"]);
            if (!o.images.empty())
                WriteDifference(o.images, FileStem(s, "gpu"), run.image, ref.image);
        }
        report["rows"].push_back(row);
    }
    WriteReportIfNamed(o.output, report);
}

}  // namespace

void AddAccuracyBench(CLI::App& bench, int* exitCode) {
    auto o = std::make_shared<AccuracyOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "accuracy",
        "Accuracy against time: depth, samples, triangle/sphere tests, ray offsets, builders, "
        "float vs double; error against a double-precision reference (docs/accuracy.md)");
    cmd->add_option("--size", o->size,
                    "Image size WxH (default 480x270 with the CPU, 1280x720 with cuda only)");
    cmd->add_option("--backend", o->backend, "cpu, cuda or both")
        ->check(CLI::IsMember({"cpu", "cuda", "both"}))
        ->capture_default_str();
    cmd->add_option("--cpu-frames", o->cpuFrames, "Timed CPU frames per setting (median)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    cmd->add_option("--gpu-frames", o->gpuFrames, "Timed GPU frames per setting (median)")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    cmd->add_option("--images", o->images,
                    "Write the references and the difference images (x4) into this folder");
    cmd->add_option("-o,--output", o->output, "Write the results as JSON here")
        ->check(WritableFile());
    cmd->callback([o, exitCode] {
        std::string why;
        if (o->backend != "cpu" && !CudaBackendAvailable(&why))
            throw InputError("bench accuracy --backend", o->backend, why + "; use --backend cpu");
        RunAccuracyBench(*o);
        *exitCode = kExitOk;
    });
}

}  // namespace rtrt
