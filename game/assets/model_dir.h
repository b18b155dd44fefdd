#pragma once
#include <string>

namespace rtrt {

// Where tools/fetch_models.sh stores the real models: $RTRT_MODEL_DIR, else the build's default
// (<source>/.cache/models).
std::string ModelDir();

// Where the project's own scenes and models are (scenes/, models/): $RTRT_ASSET_DIR, else the
// installed share/rtrt beside the running program's bin/, else the source tree's assets/.
std::string AssetDir();

// A model path from a scene file: "@models/NAME" names a fetched model; anything else is
// relative to the scene file's folder (or absolute).
std::string ResolveModelPath(const std::string& spec, const std::string& sceneDir);

}  // namespace rtrt
