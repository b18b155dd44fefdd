#include "game/app/controls.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace rtrt {

std::span<const Control> Controls() {
    static const Control kControls[] = {
        {GLFW_KEY_1, "1", Action::kSpawnSphere, "spawn a sphere"},
        {GLFW_KEY_2, "2", Action::kSpawnTeapot, "spawn a teapot"},
        {GLFW_KEY_3, "3", Action::kSpawnDragon, "spawn a dragon"},
        {GLFW_KEY_4, "4", Action::kSpawnGlassSphere, "spawn a glass sphere"},
        {GLFW_KEY_5, "5", Action::kSpawnMirrorBox, "spawn a mirror box"},
        {GLFW_KEY_6, "6", Action::kSpawnWalker, "spawn a walking character"},
        {GLFW_KEY_DELETE, "Delete", Action::kDeleteSelected, "delete the picked object"},
        {GLFW_KEY_R, "R", Action::kRotateSelected, "rotate the picked object 15 degrees"},
        {GLFW_KEY_SPACE, "Space", Action::kPause, "pause / resume"},
        {GLFW_KEY_N, "N", Action::kStep, "one step while paused"},
        {GLFW_KEY_LEFT_BRACKET, "[", Action::kSlower, "half the time scale"},
        {GLFW_KEY_RIGHT_BRACKET, "]", Action::kFaster, "double the time scale"},
        {GLFW_KEY_PAGE_DOWN, "PageDown", Action::kNextScene, "next scene"},
        {GLFW_KEY_PAGE_UP, "PageUp", Action::kPreviousScene, "previous scene"},
        {GLFW_KEY_F12, "F12", Action::kScreenshot, "screenshot (rtrt-screenshot-N.png)"},
        {GLFW_KEY_F1, "F1", Action::kToggleHelp, "this help"},
        {GLFW_KEY_F2, "F2", Action::kToggleOverlay, "overlay on / off"},
        {GLFW_KEY_F11, "F11", Action::kFullscreen, "fullscreen"},
        {GLFW_KEY_V, "V", Action::kVsync, "vsync on / off"},
        {GLFW_KEY_TAB, "Tab", Action::kOrbitMode, "fly / orbit camera"},
        {GLFW_KEY_F5, "F5", Action::kShadows, "shadows on / off"},
        {GLFW_KEY_F6, "F6", Action::kReflection, "reflection on / off"},
        {GLFW_KEY_F7, "F7", Action::kRefraction, "refraction on / off"},
        {GLFW_KEY_F8, "F8", Action::kNextView, "view: shaded, normals, depth, heatmap"},
        {GLFW_KEY_EQUAL, "=", Action::kDepthUp, "max depth + 1"},
        {GLFW_KEY_MINUS, "-", Action::kDepthDown, "max depth - 1"},
        {GLFW_KEY_PERIOD, ".", Action::kExposureUp, "exposure + 1/2 EV"},
        {GLFW_KEY_COMMA, ",", Action::kExposureDown, "exposure - 1/2 EV"},
        {GLFW_KEY_B, "B", Action::kBackend, "CPU / CUDA back end"},
        {GLFW_KEY_ESCAPE, "Escape", Action::kQuit, "quit"},
    };
    return kControls;
}

int KeyByName(const std::string& name) {
    for (const Control& c : Controls())
        if (name == c.keyName) return c.key;
    if (name.size() == 1 && name[0] >= 'A' && name[0] <= 'Z') return GLFW_KEY_A + (name[0] - 'A');
    if (name == "Shift") return GLFW_KEY_LEFT_SHIFT;
    return -1;
}

}  // namespace rtrt
