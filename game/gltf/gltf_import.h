#pragma once
// glTF 2.0 files (.gltf with its buffers and images, or .glb) through tinygltf: meshes become
// BLASes (one per triangle primitive), materials rtrt's Blinn-Phong (the mapping is in the
// README), base-colour images textures, the node hierarchy entities with transforms, node TRS
// animations keyframe clips, KHR_lights_punctual lights rtrt lights, and the first perspective
// camera rtrt's camera. What rtrt does not support gets one warning each on stderr.
#include <optional>
#include <string>

#include "game/gltf/gltf_asset.h"
#include "game/scene/loaded_scene.h"

namespace rtrt {

// True when PATH ends in .gltf or .glb (any case).
bool IsGltfPath(const std::string& path);

// Reads PATH and adds its BLASes, materials and textures to `scene` (names to the name lists).
// Throws InputError (file, field, reason) for a malformed file: a bad GLB header, JSON that is not
// glTF, accessors outside their buffers, non-finite values, indices out of range, node cycles,
// missing buffers or images.
GltfAsset LoadGltfAsset(const std::string& path, LoadedScene& out);

// Adds the asset's nodes as entities under entity `parent` (an index into out.entities, -1 for
// none) whose initial world matrix is parentWorld, and its lights, placed there, to the scene.
// Returns the first camera (in node order) placed the same way, if the file has one. The
// instance's animation starts `phase` seconds in; each instance has its own animators, so
// instances play independently.
std::optional<Camera> InstantiateGltf(const GltfAsset& asset, LoadedScene& out, int32_t parent,
                                      const glm::mat4& parentWorld, double phase = 0.0);

// A glTF file as a whole scene (rtrt render/play/info x.glb): its first camera, or one that
// frames the scene along -z; its lights, or one white directional light when it has none.
LoadedScene LoadGltfScene(const std::string& path);

}  // namespace rtrt
