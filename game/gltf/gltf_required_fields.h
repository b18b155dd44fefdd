#pragma once
// The fields glTF 2.0 requires (and the enumerations it fixes) of the objects rtrt reads, checked
// before tinygltf loads the file: tinygltf's own messages for them name no element ("'count'
// property is missing in Accessor.") or none at all (a skin without joints).
#include <string>

#include "game/scene/json_fields.h"

namespace rtrt {

// Throws InputError naming FILE and the field ("accessors[3].count") for a required field that
// is missing or a value outside its enumeration. The kinds of fields present are checked before
// (gltf_precheck.cpp); a field of another kind is left to that check.
void CheckRequiredGltfFields(const std::string& file, const Json& root);

}  // namespace rtrt
