#include "engine/render_rt/render_settings.h"

#include <charconv>

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

bool ChooseGpus(const std::string& choice, std::vector<int>* devices, std::string* why) {
    const uint32_t present = CudaDeviceCount();
    uint32_t count = 0;
    if (choice == "all") {
        count = present;
    } else {
        const char* end = choice.data() + choice.size();
        const auto [at, error] = std::from_chars(choice.data(), end, count);
        if (error != std::errc() || at != end || count == 0) {
            if (why) *why = "expected a number of GPUs (1, 2, ...) or all, got \"" + choice + "\"";
            return false;
        }
    }
    if (count == 0 || count > present) {
        if (why) {
            *why = present == 0 ? std::string(
                                      "this machine has no usable CUDA device; leave out "
                                      "--gpus to render on the CPU back end")
                                : "this machine has " + std::to_string(present) + " CUDA device" +
                                      (present == 1 ? "" : "s") + "; use --gpus " +
                                      std::to_string(present) + " or --gpus all";
        }
        return false;
    }
    devices->clear();
    for (uint32_t d = 0; d < count; ++d) devices->push_back(int(d));
    return true;
}

}  // namespace rtrt
