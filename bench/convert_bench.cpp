// `rtrt bench convert`: the offline pipeline of `rtrt convert` per model — hash, parse, BLAS
// build, write — and the load of the written .rtmodel, medians of several runs, with SAH cost.
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/bench_commands.h"
#include "bench/bench_report.h"
#include "engine/core/content_hash.h"
#include "engine/core/error.h"
#include "engine/core/interrupt.h"
#include "engine/core/timer.h"
#include "game/assets/mesh_io.h"
#include "game/assets/model_cache.h"
#include "game/assets/model_dir.h"
#include "game/cli/heap_tuning.h"

namespace rtrt {
namespace {

namespace fs = std::filesystem;

struct ConvertBenchOptions {
    std::vector<std::string> models{"dragon_res4", "dragon_res3", "dragon_res2", "dragon"};
    std::string builder = "binned";
    int runs = 5;
    std::string output;
};

// The bench's scratch folder, removed at the end, on an error and on an interrupt. A new folder
// of a name no one can foresee (mkdtemp): a fixed name in /tmp let another user's link there send
// the models elsewhere, and a folder already there was removed with what it held.
class ScratchFolder {
  public:
    explicit ScratchFolder(const std::string& prefix) {
        std::error_code ec;
        const fs::path base = fs::temp_directory_path(ec);
        if (ec)
            throw OutputError("TMPDIR", "no folder for temporary files (" + ec.message() +
                                            "): set TMPDIR to a folder that exists");
        std::string pattern = (base / (prefix + "XXXXXX")).string();
        TemporariesLock lock;
        if (!::mkdtemp(pattern.data())) throw OutputError(pattern, std::strerror(errno));
        path_ = pattern;
        lock.Register(path_.string());
    }
    ~ScratchFolder() {
        TemporariesLock lock;
        std::error_code ignored;
        fs::remove_all(path_, ignored);
        lock.Unregister(path_.string());
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;
    const fs::path& Path() const { return path_; }

  private:
    fs::path path_;
};

struct Run {
    double hashMs, parseMs, buildMs, writeMs, loadMs, totalMs;
};

void RunConvertBench(const ConvertBenchOptions& o, const nlohmann::json& machine) {
    KeepLargeAllocationsInHeap();  // as rtrt convert does
    BvhBuildOptions options;
    ParseBuilder(o.builder, &options.builder);
    const ScratchFolder scratch("rtrt_bench_convert_");
    const fs::path& dir = scratch.Path();
    nlohmann::json report;
    report["machine"] = machine;
    report["builder"] = o.builder;
    report["timing"] =
        "wall clock per stage, median of the runs; total = hash + parse + build "
        "+ write, what rtrt convert does";
    std::printf("rtrt bench convert: %s builder, median of %d runs (ms)\n", o.builder.c_str(),
                o.runs);
    std::printf("%-12s %10s %7s %8s %8s %7s %8s | %8s %9s %8s\n", "model", "triangles", "hash",
                "parse", "build", "write", "total", "load", "SAH cost", "MB");
    // Every model parsed once before any is timed: a bad file late in the list fails the command
    // before its work, not after the rows of the models before it.
    for (const std::string& name : o.models)
        if (const std::string path = BenchModelFile(name); fs::exists(path)) LoadMesh(path);
    for (const std::string& name : o.models) {
        const std::string path = BenchModelFile(name);
        if (!fs::exists(path)) {
            SkipMissingModel(report, name);
            continue;
        }
        const std::string out = (dir / (name + ".rtmodel")).string();
        std::vector<double> hash, parse, build, write, load, total;
        MeshModel model;
        for (int r = 0; r < o.runs; ++r) {
            fs::remove(out);
            Stopwatch timer, all;
            const uint64_t sourceHash = HashFile(path);
            hash.push_back(timer.Milliseconds());
            model = BuildMeshModel(path, options, sourceHash);
            parse.push_back(model.parseMs);
            build.push_back(model.buildMs);
            timer.Restart();
            WriteRtModel(out, model.blas, model.info);
            write.push_back(timer.Milliseconds());
            total.push_back(all.Milliseconds());
            timer.Restart();
            const Blas loaded = ReadRtModel(out);
            load.push_back(timer.Milliseconds());
        }
        const double mb = double(fs::file_size(out)) / 1e6;
        std::printf("%-12s %10u %7.1f %8.1f %8.1f %7.1f %8.1f | %8.1f %9.2f %8.1f\n", name.c_str(),
                    model.blas.SourcePrimCount(), Median(hash), Median(parse), Median(build),
                    Median(write), Median(total), Median(load), model.info.sahCost, mb);
        report["models"].push_back(
            {{"model", name},
             {"triangles", model.blas.SourcePrimCount()},
             {"hash_ms", Median(hash)},
             {"parse_ms", Median(parse)},
             {"build_ms", Median(build)},
             {"write_ms", Median(write)},
             {"convert_ms", Median(total)},
             {"convert_ms_min", *std::min_element(total.begin(), total.end())},
             {"load_ms", Median(load)},
             {"sah_cost", model.info.sahCost},
             {"file_bytes", fs::file_size(out)},
             {"runs", o.runs}});
    }
    WriteReportIfNamed(o.output, report);
}

}  // namespace

void AddConvertBench(CLI::App& bench, int* exitCode, nlohmann::json (*machineInfo)()) {
    auto options = std::make_shared<ConvertBenchOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "convert",
        "rtrt convert's pipeline per model (hash, parse, build, write) and the load "
        "of the .rtmodel it writes");
    cmd->add_option("--models", options->models, "dragon_res4, dragon_res3, dragon_res2, dragon")
        ->check(CLI::IsMember({"dragon_res4", "dragon_res3", "dragon_res2", "dragon"}))
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--builder", options->builder, "binned, sweep, centroid or sbvh")
        ->check(CLI::IsMember({"binned", "sweep", "centroid", "sbvh"}))
        ->capture_default_str();
    cmd->add_option("--runs", options->runs, "Runs per model (medians reported)")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    cmd->add_option("-o,--output", options->output, "Write the results as JSON here")
        ->check(WritableFile());
    cmd->callback([options, exitCode, machineInfo] {
        DropRepeats(&options->models);
        CheckBenchModels(options->models, options->output);
        RunConvertBench(*options, machineInfo());
        *exitCode = kExitOk;
    });
}

}  // namespace rtrt
