#include "engine/render_rt/render_settings.h"

namespace rtrt {

bool ChooseBackend(const std::string& choice, Backend* backend, std::string* why) {
    if (choice == "cpu") {
        *backend = Backend::kCpu;
        return true;
    }
    if (choice != "cuda" && choice != "auto") {
        if (why) *why = "expected auto, cpu or cuda, got \"" + choice + "\"";
        return false;
    }
    std::string unavailable;
    const bool cuda = CudaBackendAvailable(&unavailable);
    if (choice == "cuda" && !cuda) {
        if (why) *why = unavailable;
        return false;
    }
    *backend = cuda ? Backend::kCuda : Backend::kCpu;
    return true;
}

}  // namespace rtrt
