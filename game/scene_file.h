#pragma once
// rtrt scene files (JSON; the format is documented in the README).
#include <optional>
#include <string>

#include "engine/render_rt/render_scene.h"

namespace rtrt {

struct LoadedScene {
    RenderScene scene;
    std::optional<uint32_t> width, height;  // the file's "image" size, if it gives one
};

// Reads a scene file and builds its BLASes and TLAS. Throws InputError naming the file, the
// field (e.g. "instances[2].scale") and the reason for anything malformed.
LoadedScene LoadSceneFile(const std::string& path);

// Same, from JSON text; `name` stands for the file in messages and `baseDir` resolves paths.
LoadedScene ParseScene(const std::string& text, const std::string& name,
                       const std::string& baseDir);

}  // namespace rtrt
