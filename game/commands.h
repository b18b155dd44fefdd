#pragma once
// The rtrt subcommands. Each registers itself on the app and sets *exitCode when it runs.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

namespace rtrt {

// Exit statuses scripts can rely on.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;   // the work itself failed (GPU error, I/O error)
inline constexpr int kExitBadInput = 2;  // bad command line, scene, model or output path

void AddRenderCommand(CLI::App& app, int* exitCode);
void AddBenchCommand(CLI::App& app, int* exitCode);
void AddPlayCommand(CLI::App& app, int* exitCode);
// `rtrt bench frame`, registered by AddBenchCommand.
void AddFrameBench(CLI::App& bench, int* exitCode);
// `rtrt bench accuracy`, registered by AddBenchCommand.
void AddAccuracyBench(CLI::App& bench, int* exitCode);
void AddConvertCommand(CLI::App& app, int* exitCode);
void AddInfoCommand(CLI::App& app, int* exitCode);
// `rtrt bench convert`, registered by AddBenchCommand; machineInfo describes the machine for the
// JSON report.
void AddConvertBench(CLI::App& bench, int* exitCode, nlohmann::json (*machineInfo)());

// Parses WIDTHxHEIGHT (1..16384 each); InputError naming --size otherwise.
void ParseSize(const std::string& text, uint32_t* width, uint32_t* height);

}  // namespace rtrt
