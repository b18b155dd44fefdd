#pragma once
// The "deform" field of a scene file's instances and spawners: a procedural deformation of the
// instance's model, {"wave": {...}} or {"twist": {...}}.
#include <string>

#include "engine/geometry/aabb.h"
#include "engine/render_rt/deformation.h"
#include "game/scene/json_fields.h"

namespace rtrt {

// The deformation J (at PATH of FILE) asks for, over a model whose rest bounds are MODEL (its
// centre is the default centre). Throws InputError naming the field for anything malformed.
ProceduralDeform ParseDeform(const Json& j, const std::string& path, const Aabb& model,
                             const std::string& file);

}  // namespace rtrt
