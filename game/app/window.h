#pragma once
// A GLFW window with an OpenGL 3.3 core context, vsync and fullscreen toggles, and its input
// delivered into an Input.
#include <string>

#include "game/app/input.h"

struct GLFWwindow;

namespace rtrt {

class Window {
  public:
    // Throws std::runtime_error saying why (no display, no OpenGL 3.3) if it cannot open.
    Window(int width, int height, const std::string& title, bool vsync);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    bool ShouldClose() const;
    void RequestClose();
    void PollEvents();  // starts a new Input frame, then collects events
    void SwapBuffers();
    ivec2 FramebufferSize() const;
    void ToggleFullscreen();
    void SetVsync(bool on);
    bool Vsync() const { return vsync_; }
    bool Fullscreen() const { return fullscreen_; }
    Input& GetInput() { return input_; }
    const Input& GetInputConst() const { return input_; }
    GLFWwindow* Handle() const { return window_; }
    std::string Renderer() const;  // GL_RENDERER, e.g. "llvmpipe" or the GPU's name

  private:
    GLFWwindow* window_ = nullptr;
    Input input_;
    bool vsync_ = true;
    bool fullscreen_ = false;
    int windowedX_ = 0, windowedY_ = 0, windowedW_ = 0, windowedH_ = 0;
};

}  // namespace rtrt
