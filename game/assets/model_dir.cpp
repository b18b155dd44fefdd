#include "game/assets/model_dir.h"

#include <cstdlib>
#include <filesystem>

namespace rtrt {

std::string ModelDir() {
    if (const char* env = std::getenv("RTRT_MODEL_DIR"); env && *env) return env;
    return RTRT_DEFAULT_MODEL_DIR;
}

std::string AssetDir() {
    if (const char* env = std::getenv("RTRT_ASSET_DIR"); env && *env) return env;
    std::error_code error;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) {
        const std::filesystem::path installed = exe.parent_path().parent_path() / "share/rtrt";
        if (std::filesystem::is_directory(installed / "models", error)) return installed.string();
    }
    return RTRT_DEFAULT_ASSET_DIR;
}

std::string ResolveModelPath(const std::string& spec, const std::string& sceneDir) {
    constexpr std::string_view kPrefix = "@models/";
    if (spec.starts_with(kPrefix)) return ModelDir() + "/" + spec.substr(kPrefix.size());
    std::filesystem::path path(spec);
    if (path.is_absolute() || sceneDir.empty()) return spec;
    return (std::filesystem::path(sceneDir) / path).string();
}

}  // namespace rtrt
