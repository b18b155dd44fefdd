#pragma once
// The --backend option of the benchmarks that time either back end, and what it resolves to.
#include <string>

#include "engine/render_rt/render_settings.h"

namespace CLI {
class App;
}

namespace rtrt {

// Adds --backend: "auto" (CUDA when usable), "cuda" or "cpu"; without withAuto, "cuda" or "cpu".
void AddBackendOption(CLI::App* command, std::string* backend, bool withAuto = true);

// The back end *backend names, written back as "cuda" or "cpu" (what the reports record). An
// InputError naming --backend where it cannot run here.
Backend ResolveBackendOption(std::string* backend);

}  // namespace rtrt
