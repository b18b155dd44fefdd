#include "bench/backend_option.h"

#include <CLI/CLI.hpp>

#include "engine/core/error.h"

namespace rtrt {

void AddBackendOption(CLI::App* command, std::string* backend, bool withAuto) {
    if (withAuto) {
        command->add_option("--backend", *backend, "auto (CUDA when usable), cuda or cpu")
            ->check(CLI::IsMember({"auto", "cuda", "cpu"}))
            ->capture_default_str();
    } else {
        command->add_option("--backend", *backend, "cuda or cpu")
            ->check(CLI::IsMember({"cuda", "cpu"}))
            ->capture_default_str();
    }
}

Backend ResolveBackendOption(std::string* backend) {
    Backend chosen;
    std::string why;
    if (!ChooseBackend(*backend, &chosen, &why))
        throw InputError("--backend", *backend, why + "; use --backend cpu");
    *backend = chosen == Backend::kCuda ? "cuda" : "cpu";
    return chosen;
}

}  // namespace rtrt
