#pragma once
// The rtrt subcommands. Each registers itself on the app and sets *exitCode when it runs;
// `rtrt bench` is registered by bench/bench_commands.h.
#include <CLI/CLI.hpp>

#include "game/cli/cli_options.h"

namespace rtrt {

void AddRenderCommand(CLI::App& app, int* exitCode);
void AddPlayCommand(CLI::App& app, int* exitCode);
void AddConvertCommand(CLI::App& app, int* exitCode);
void AddInfoCommand(CLI::App& app, int* exitCode);
void AddFetchModelsCommand(CLI::App& app, int* exitCode);
void AddFarmCommand(CLI::App& app, int* exitCode);

}  // namespace rtrt
