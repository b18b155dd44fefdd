#include "game/assets/model_dir.h"

#include <cstdlib>
#include <filesystem>

namespace rtrt {

std::string InstalledShareDir() {
    std::error_code error;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
    if (error) return {};
    const std::filesystem::path share = exe.parent_path().parent_path() / "share/rtrt";
    return std::filesystem::is_directory(share / "scenes", error) ? share.string() : std::string();
}

std::string ModelDir() {
    if (const char* env = std::getenv("RTRT_MODEL_DIR"); env && *env) return env;
    if (InstalledShareDir().empty()) return RTRT_DEFAULT_MODEL_DIR;
#ifdef RTRT_CONFIGURED_MODEL_DIR
    return RTRT_CONFIGURED_MODEL_DIR;
#endif
    if (const char* data = std::getenv("XDG_DATA_HOME"); data && *data)
        return std::string(data) + "/rtrt/models";
    const char* home = std::getenv("HOME");
    return std::string(home && *home ? home : ".") + "/.local/share/rtrt/models";
}

std::string AssetDir() {
    if (const char* env = std::getenv("RTRT_ASSET_DIR"); env && *env) return env;
    const std::string installed = InstalledShareDir();
    return installed.empty() ? std::string(RTRT_DEFAULT_ASSET_DIR) : installed;
}

std::string FetchModelsScript() {
    const std::string installed = InstalledShareDir();
    return installed.empty() ? std::string(RTRT_DEFAULT_ASSET_DIR) + "/../tools/fetch_models.sh"
                             : installed + "/tools/fetch_models.sh";
}

std::string MissingModelReason(const std::string& spec, const std::string& sceneDir) {
    if (spec.empty()) return "is empty; name a model file";  // it read as the scene's folder
    constexpr std::string_view kPrefix = "@models/";
    std::error_code error;
    if (!spec.starts_with(kPrefix)) {
        // Only a file known to be absent: one that cannot be looked at is the loader's to name.
        const std::string path = ResolveModelPath(spec, sceneDir);
        // A folder fails here, named as such: its name has no model extension to go by.
        if (std::filesystem::is_directory(path, error))
            return path + " is not a regular file (a folder)";
        if (std::filesystem::exists(path, error) || error) return {};
        const bool relative = std::filesystem::path(spec).is_relative() && !sceneDir.empty();
        return "no file " + path +
               (relative ? " (a relative path starts at the scene file's folder)" : "");
    }
    const std::string dir = ModelDir();
    const std::string path = dir + "/" + spec.substr(kPrefix.size());
    if (std::filesystem::is_directory(path, error))
        return path + " is not a regular file (a folder)";
    if (std::filesystem::exists(path, error)) return {};
    return spec + " not found in " + dir + " (run rtrt fetch-models, or set RTRT_MODEL_DIR)";
}

std::string ResolveModelPath(const std::string& spec, const std::string& sceneDir) {
    constexpr std::string_view kPrefix = "@models/";
    if (spec.starts_with(kPrefix)) return ModelDir() + "/" + spec.substr(kPrefix.size());
    std::filesystem::path path(spec);
    if (path.is_absolute() || sceneDir.empty()) return spec;
    return (std::filesystem::path(sceneDir) / path).string();
}

}  // namespace rtrt
