#pragma once
// `rtrt bench` and its subcommands. Each registers itself and sets *exitCode when it runs.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/geometry/triangle_mesh.h"
#include "game/cli/cli_options.h"

namespace rtrt {

void AddBenchCommand(CLI::App& app, int* exitCode);
// Loads a benchmark model of the paper scene (cube, teapot, dragon_res4 .. dragon), fitted to
// extent 5; false when its file is missing (tools/fetch_models.sh fetches it).
bool LoadBenchModel(const std::string& name, TriangleMesh* mesh);
// A benchmark model as LoadBenchModels read it: no mesh when its file is missing.
struct BenchModel {
    std::string name;
    std::optional<TriangleMesh> mesh;
    double loadMs = 0.0;
};
// Every model of a benchmark, read before any is measured: a bad file late in the list fails the
// command before its work, not after the rows of the models before it.
std::vector<BenchModel> LoadBenchModels(const std::vector<std::string>& names);
// The file a benchmark model is read from ("" for the cube, which is made, not read).
std::string BenchModelFile(const std::string& name);
// InputError unless at least one of models is there to run: a benchmark of none measures nothing
// (missing ones among others are skipped with a line that says so); and when `output` (the
// report's file, if any) names one of their files, before any work rather than at the report.
void CheckBenchModels(const std::vector<std::string>& models, const std::string& output);
// Says that model NAME is skipped because its file is missing, on stdout and in the report's
// "skipped" list (so that a report without the model says why).
void SkipMissingModel(nlohmann::json& report, const std::string& name);
// Each name once, in the order first given (--models cube,cube measures the cube once: the report
// holds one entry per name).
void DropRepeats(std::vector<std::string>* names);
// The --models option of the paper-scene benchmarks: a comma-separated subset of those models.
CLI::Option* AddModelsOption(CLI::App* command, std::vector<std::string>* models);
// `rtrt bench embree`, registered by AddBenchCommand.
void AddEmbreeBench(CLI::App& bench, int* exitCode);
// `rtrt bench frame`, registered by AddBenchCommand.
void AddFrameBench(CLI::App& bench, int* exitCode);
// `rtrt bench split`, registered by AddBenchCommand.
void AddSplitBench(CLI::App& bench, int* exitCode);
// `rtrt bench deform`, registered by AddBenchCommand.
void AddDeformBench(CLI::App& bench, int* exitCode);
// `rtrt bench soak`, registered by AddBenchCommand.
void AddSoakBench(CLI::App& bench, int* exitCode);
// `rtrt bench materials`, registered by AddBenchCommand.
void AddMaterialsBench(CLI::App& bench, int* exitCode);
// `rtrt bench accuracy`, registered by AddBenchCommand.
void AddAccuracyBench(CLI::App& bench, int* exitCode);
// `rtrt bench convert`, registered by AddBenchCommand; machineInfo describes the machine for the
// JSON report.
void AddConvertBench(CLI::App& bench, int* exitCode, nlohmann::json (*machineInfo)());

}  // namespace rtrt
