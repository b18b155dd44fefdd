#pragma once
#include <string>

namespace rtrt {

// Where the real models are (tools/fetch_models.sh and `rtrt fetch-models` put them there):
// $RTRT_MODEL_DIR; else, for an installed rtrt, the user's data folder ($XDG_DATA_HOME/rtrt/models,
// else ~/.local/share/rtrt/models); else, run from its build tree, <source>/.cache/models.
std::string ModelDir();

// The installed share/rtrt beside the running program's bin/, or empty when rtrt runs from its
// build tree.
std::string InstalledShareDir();

// The script that fetches the models (installed in share/rtrt/tools, or the tree's tools/).
std::string FetchModelsScript();

// Why SPEC, from a scene file in SCENEDIR, cannot be used when it is empty, names a fetched model
// that is not there ("@models/X not found in DIR (run rtrt fetch-models, or set RTRT_MODEL_DIR)")
// or a file that does not exist, or is a folder, else empty.
std::string MissingModelReason(const std::string& spec, const std::string& sceneDir);

// Where the project's own scenes and models are (scenes/, models/): $RTRT_ASSET_DIR, else the
// installed share/rtrt beside the running program's bin/, else the source tree's assets/.
std::string AssetDir();

// A model path from a scene file: "@models/NAME" names a fetched model; anything else is
// relative to the scene file's folder (or absolute).
std::string ResolveModelPath(const std::string& spec, const std::string& sceneDir);

}  // namespace rtrt
