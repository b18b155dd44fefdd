#pragma once
// The window's keys, in one table: the input handling, the on-screen help panel, the README and
// test scripts (which name keys as written here) all read it.
#include <span>
#include <string>

namespace rtrt {

enum class Action {
    kSpawnSphere,
    kSpawnTeapot,
    kSpawnDragon,
    kSpawnGlassSphere,
    kSpawnMirrorBox,
    kSpawnWalker,
    kDeleteSelected,
    kRotateSelected,
    kPause,
    kStep,
    kSlower,
    kFaster,
    kNextScene,
    kPreviousScene,
    kScreenshot,
    kToggleHelp,
    kToggleOverlay,
    kFullscreen,
    kVsync,
    kOrbitMode,
    kShadows,
    kReflection,
    kRefraction,
    kNextView,
    kDepthUp,
    kDepthDown,
    kExposureUp,
    kExposureDown,
    kBackend,
    kQuit,
};

struct Control {
    int key;  // GLFW key code
    const char* keyName;
    Action action;
    const char* what;
};

std::span<const Control> Controls();
// The GLFW key code of a key name from the table ("F5", "Space", "1"...), or -1.
int KeyByName(const std::string& name);

// Not in the table because they are held or use the mouse: WASD + Q/E move (Shift: faster), the
// right mouse button looks around (fly) or turns around the target (orbit), the wheel zooms in
// orbit mode, the left button picks an object and drags it.
inline constexpr const char* kMouseHelp =
    "W A S D, Q E: move (Shift: 4x)   right mouse: look / orbit   wheel: orbit distance\n"
    "left click: pick   left drag: move the picked object";

}  // namespace rtrt
