#pragma once
// rtrt scene files (JSON; the format is documented in the README).
#include <string>

#include "game/scene/loaded_scene.h"

namespace rtrt {

// Reads a scene file (or a glTF file, .gltf or .glb: gltf_import.h; or "default", where no file
// of that name exists: the built-in scene) and builds its BLASes and TLAS. Throws InputError naming
// the file, the field (e.g. "instances[2].scale") and the reason for anything malformed.
LoadedScene LoadSceneFile(const std::string& path);

// The file a scene argument names: ARGUMENT itself when such a file exists, else the project's
// scene of that name (NAME or NAME.json, installed or in the tree), else ARGUMENT unchanged (so
// "default" stays the built-in scene and a missing file fails in LoadSceneFile).
std::string ScenePathFor(const std::string& argument);

// Same, from JSON text; `name` stands for the file in messages and `baseDir` resolves paths.
LoadedScene ParseScene(const std::string& text, const std::string& name,
                       const std::string& baseDir);

}  // namespace rtrt
