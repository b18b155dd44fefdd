#pragma once
// The "camera_path" field of a scene file: camera keys {time, position, look_at} that the camera
// follows, interpolated linearly between keys.
#include <string>
#include <vector>

#include "game/scene/json_fields.h"
#include "game/scene/loaded_scene.h"

namespace rtrt {

// The keys J (the camera_path field of FILE) gives, for a camera whose up is UP. Throws
// InputError naming the key and field for anything malformed, for keys out of time order, and
// for a path on which the view direction vanishes or turns parallel to UP.
std::vector<CameraKey> ParseCameraPath(const Json& j, vec3 up, const std::string& file);

}  // namespace rtrt
