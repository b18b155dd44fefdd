// `rtrt convert MODEL -o OUT.rtmodel [--builder NAME]`: parses a mesh, builds its BLAS and stores
// both in the tracer's layout (engine/bvh/blas/rtmodel.h), so that loading it later costs one read.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "engine/core/content_hash.h"
#include "engine/core/error.h"
#include "engine/core/output_file.h"
#include "engine/core/timer.h"
#include "game/assets/model_cache.h"
#include "game/cli/commands.h"
#include "game/cli/heap_tuning.h"
#include "game/cli/progress_bar.h"

namespace rtrt {
namespace {

struct ConvertOptions {
    std::string model;
    std::string output;
    std::string builder = "binned";
};

constexpr int kStages = 4;  // hash, parse, build, write

// The bar is for people watching a terminal; logs and scripts get the result lines only.
const bool kShowProgress = isatty(STDERR_FILENO) != 0;

void ShowStage(const char* stage) {
    if (!kShowProgress) return;
    static const char* const kNames[kStages] = {"hash", "parse", "build", "write"};
    int done = 0;
    while (done < kStages && std::string(kNames[done]) != stage) ++done;
    const std::string what = std::string(stage) + "...";
    DrawProgressBar("convert", done, kStages, what.c_str());
}

// Everything the command line can get wrong is checked before the slow work starts.
void CheckPaths(const ConvertOptions& o) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (IsRtModelPath(o.model))
        throw InputError(o.model, "", "is already an .rtmodel (rtrt info shows what it holds)");
    if (!fs::exists(o.model, ec)) throw InputError(o.model, "", "no such file");
    if (!IsRtModelPath(o.output))
        throw InputError("--output", "",
                         "expected a file name ending in .rtmodel, got \"" + o.output + "\"");
    const fs::path folder = fs::path(o.output).parent_path();
    if (!folder.empty() && !fs::is_directory(folder, ec))
        throw InputError("--output", "", "folder " + folder.string() + " does not exist");
    CheckOutputPath(o.output);
}

void Convert(const ConvertOptions& o) {
    BvhBuildOptions options;
    ParseBuilder(o.builder, &options.builder);
    Stopwatch total;
    ShowStage("hash");
    Stopwatch timer;
    const uint64_t sourceHash = HashFile(o.model);
    const double hashMs = timer.Milliseconds();
    const MeshModel model = BuildMeshModel(o.model, options, sourceHash, &ShowStage);
    ShowStage("write");
    timer.Restart();
    WriteRtModel(o.output, model.blas, model.info);
    const double writeMs = timer.Milliseconds();
    if (kShowProgress) DrawProgressBar("convert", kStages, kStages, "done");
    const uint64_t bytes = std::filesystem::file_size(o.output);
    std::printf("rtrt: wrote %s (%u triangles, %u source vertices, %.1f MB)\n", o.output.c_str(),
                model.blas.SourcePrimCount(), model.info.sourceVertexCount, double(bytes) / 1e6);
    std::printf("rtrt: %s builder, SAH cost %.2f\n", o.builder.c_str(), model.info.sahCost);
    std::printf("rtrt: hash %.1f ms, parse %.1f ms, build %.1f ms, write %.1f ms, total %.1f ms\n",
                hashMs, model.parseMs, model.buildMs, writeMs, total.Milliseconds());
}

void RunConvert(const ConvertOptions& o) {
    CheckPaths(o);
    KeepLargeAllocationsInHeap();
    try {
        Convert(o);
    } catch (...) {
        if (kShowProgress) std::fputc('\n', stderr);  // the error gets a line of its own
        throw;
    }
}

}  // namespace

void AddConvertCommand(CLI::App& app, int* exitCode) {
    auto options = std::make_shared<ConvertOptions>();
    CLI::App* cmd = app.add_subcommand(
        "convert",
        "Build a model's BVH offline and store it with the triangles as an .rtmodel file");
    cmd->add_option("model", options->model, "Mesh file: .obj, .ply or .ply.gz")->required();
    cmd->add_option("-o,--output", options->output, "The .rtmodel file to write")->required();
    cmd->add_option("--builder", options->builder,
                    "BVH builder: binned, sweep, centroid or sbvh (spatial splits)")
        ->check(CLI::IsMember({"binned", "sweep", "centroid", "sbvh"}))
        ->capture_default_str();
    cmd->callback([options, exitCode] {
        RunConvert(*options);
        *exitCode = kExitOk;
    });
}

}  // namespace rtrt
