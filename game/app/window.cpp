#include "game/app/window.h"

#define GLFW_INCLUDE_NONE
#include <GL/gl.h>
#include <GLFW/glfw3.h>

#include <stdexcept>

namespace rtrt {
namespace {

Input& InputOf(GLFWwindow* w) { return *static_cast<Input*>(glfwGetWindowUserPointer(w)); }

std::string LastGlfwError() {
    const char* text = nullptr;
    glfwGetError(&text);
    return text ? text : "unknown reason";
}

}  // namespace

Window::Window(int width, int height, const std::string& title, bool vsync) : vsync_(vsync) {
    if (!glfwInit())
        throw std::runtime_error("cannot open a window (" + LastGlfwError() +
                                 "); use --headless, or run under a display or xvfb-run");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        const std::string why = LastGlfwError();
        glfwTerminate();
        throw std::runtime_error("cannot create an OpenGL 3.3 core window (" + why +
                                 "); use --headless");
    }
    glfwMakeContextCurrent(window_);
    SetVsync(vsync);
    glfwSetWindowUserPointer(window_, &input_);
    // Installed before Dear ImGui's, which calls them in turn.
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
        if (action != GLFW_REPEAT) InputOf(w).Key(key, action == GLFW_PRESS);
    });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
        InputOf(w).MouseMove(vec2(float(x), float(y)));
    });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
        InputOf(w).MouseButton(button, action == GLFW_PRESS);
    });
    glfwSetScrollCallback(window_,
                          [](GLFWwindow* w, double, double dy) { InputOf(w).Scroll(float(dy)); });
}

Window::~Window() {
    glfwDestroyWindow(window_);
    glfwTerminate();
}

bool Window::ShouldClose() const { return glfwWindowShouldClose(window_); }
void Window::RequestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

void Window::PollEvents() {
    input_.BeginFrame();
    glfwPollEvents();
}

void Window::SwapBuffers() { glfwSwapBuffers(window_); }

ivec2 Window::FramebufferSize() const {
    ivec2 size;
    glfwGetFramebufferSize(window_, &size.x, &size.y);
    return size;
}

void Window::SetVsync(bool on) {
    vsync_ = on;
    glfwSwapInterval(on ? 1 : 0);
}

void Window::ToggleFullscreen() {
    if (!fullscreen_) {
        GLFWmonitor* monitor = glfwGetPrimaryMonitor();
        if (!monitor) return;
        glfwGetWindowPos(window_, &windowedX_, &windowedY_);
        glfwGetWindowSize(window_, &windowedW_, &windowedH_);
        const GLFWvidmode* mode = glfwGetVideoMode(monitor);
        glfwSetWindowMonitor(window_, monitor, 0, 0, mode->width, mode->height, mode->refreshRate);
        fullscreen_ = true;
    } else {
        glfwSetWindowMonitor(window_, nullptr, windowedX_, windowedY_, windowedW_, windowedH_, 0);
        fullscreen_ = false;
    }
    SetVsync(vsync_);  // a new video mode can reset the swap interval
}

std::string Window::Renderer() const {
    const GLubyte* name = glGetString(GL_RENDERER);
    return name ? reinterpret_cast<const char*>(name) : "unknown";
}

}  // namespace rtrt
