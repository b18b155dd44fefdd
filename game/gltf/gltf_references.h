#pragma once
// The references between a glTF file's objects, checked in its JSON before tinygltf reads it:
// tinygltf keeps an index in an int (4294967296 named texture 0) and reads a negative one as
// absent, and it decodes an image from a buffer view it never checked against its buffer (a
// view 1 GB past a 36-byte buffer crashed the decoder).
#include <string>

#include "game/scene/json_fields.h"

namespace rtrt {

// The texture slots (textureInfo objects) of a material that rtrt reads, as dotted paths inside
// it: the core ones, then the extensions'.
inline constexpr const char* kGltfTextureSlots[] = {
    "pbrMetallicRoughness.baseColorTexture",
    "pbrMetallicRoughness.metallicRoughnessTexture",
    "normalTexture",
    "occlusionTexture",
    "emissiveTexture",
    "extensions.KHR_materials_transmission.transmissionTexture",
    "extensions.KHR_materials_specular.specularTexture",
    "extensions.KHR_materials_specular.specularColorTexture",
};

// Throws InputError naming FILE and the field ("materials[0].normalTexture.index") for an index
// that names no object of its array, a buffer view that does not lie inside its buffer, a
// texCoord below 0, and a sampler's filter or wrap mode outside glTF's enumerations. Fields of
// another JSON kind are left to the kind checks (gltf_precheck.cpp), which run first.
void CheckGltfReferences(const std::string& file, const Json& root);

}  // namespace rtrt
