#pragma once
// What the user did since the last frame, fed by GLFW's callbacks or by a test script through the
// same functions, so a scripted session exercises the same controls as a person.
#include <array>
#include <vector>

#include "engine/core/math.h"

namespace rtrt {

struct Input {
    static constexpr int kKeyCount = 512;  // GLFW_KEY_LAST is 348

    std::vector<int> pressed;  // keys that went down this frame, in order (GLFW key codes)
    std::array<bool, kKeyCount> down{};
    vec2 mouse{0.0f}, mouseDelta{0.0f};
    bool leftDown = false, rightDown = false;
    bool leftPressed = false, leftReleased = false;
    float scroll = 0.0f;

    void BeginFrame() {
        pressed.clear();
        mouseDelta = vec2(0.0f);
        leftPressed = leftReleased = false;
        scroll = 0.0f;
    }
    void Key(int key, bool press) {
        if (key < 0 || key >= kKeyCount) return;
        if (press && !down[key]) pressed.push_back(key);
        down[key] = press;
    }
    void MouseMove(vec2 position) {
        mouseDelta += position - mouse;
        mouse = position;
    }
    void MouseButton(int button, bool press) {
        if (button == 0) {
            leftPressed |= press && !leftDown;
            leftReleased |= !press && leftDown;
            leftDown = press;
        } else if (button == 1) {
            rightDown = press;
        }
    }
    void Scroll(float steps) { scroll += steps; }
    bool Pressed(int key) const {
        for (int k : pressed)
            if (k == key) return true;
        return false;
    }
};

}  // namespace rtrt
