#pragma once
#include "engine/render_rt/render_scene.h"
#include "game/scene/loaded_scene.h"

namespace rtrt {

// The scene `rtrt render` and the demo show without a file: a mirror sphere, a glass sphere, a
// diffuse sphere and a box on a floor, a directional and a point light. Needs no model files.
RenderScene MakeDefaultScene();

// The same scene as one `rtrt play` plays ("default", or no scene named): its instances become
// entities that stand still.
LoadedScene MakeDefaultLoadedScene();

}  // namespace rtrt
