#include "game/app/frame_display.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "game/app/gl.h"
#include "game/assets/image_io.h"

namespace rtrt {
namespace {

// One triangle covering the viewport; image rows run top to bottom, texture rows bottom to top.
constexpr const char* kVertexShader = R"(#version 330 core
out vec2 uv;
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    uv = vec2(p.x, 1.0 - p.y);  // texture row 0 is the image's top row
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
})";

constexpr const char* kFragmentShader = R"(#version 330 core
in vec2 uv;
out vec4 color;
uniform sampler2D frame;
void main() { color = vec4(texture(frame, uv).rgb, 1.0); })";

GLuint Compile(GLenum type, const char* source) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024];
        glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
        throw std::runtime_error(std::string("display shader: ") + log);
    }
    return shader;
}

}  // namespace

FrameDisplay::FrameDisplay() {
    const GLuint vs = Compile(GL_VERTEX_SHADER, kVertexShader);
    const GLuint fs = Compile(GL_FRAGMENT_SHADER, kFragmentShader);
    program_ = glCreateProgram();
    glAttachShader(program_, vs);
    glAttachShader(program_, fs);
    glLinkProgram(program_);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program_, GL_LINK_STATUS, &ok);
    if (!ok) throw std::runtime_error("display shader: link failed");
    glGenVertexArrays(1, &vertexArray_);  // core profile draws need a vertex array bound
    glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

FrameDisplay::~FrameDisplay() {
    glDeleteTextures(1, &texture_);
    glDeleteVertexArrays(1, &vertexArray_);
    glDeleteProgram(program_);
}

bool FrameDisplay::Resize(uint32_t width, uint32_t height) {
    if (width == width_ && height == height_) return false;
    width_ = width;
    height_ = height;
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, GLsizei(width), GLsizei(height), 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, nullptr);
    return true;
}

void FrameDisplay::Upload(const Image& image, const OutputTransform& transform) {
    Resize(image.width, image.height);
    glBindTexture(GL_TEXTURE_2D, texture_);
    if (transform.exposureEv == 0.0f && transform.toneMap == ToneMap::kClamp &&
        !transform.srgbEncode) {
        // Display values: GL clamps float components to [0, 1] when it converts them to the
        // 8-bit texture.
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, GLsizei(image.width), GLsizei(image.height), GL_RGB,
                        GL_FLOAT, image.pixels.data());
        return;
    }
    const std::vector<uint8_t> bytes = EightBit(image, transform);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, GLsizei(image.width), GLsizei(image.height), GL_RGB,
                    GL_UNSIGNED_BYTE, bytes.data());
}

void FrameDisplay::Draw(int framebufferWidth, int framebufferHeight) {
    glViewport(0, 0, framebufferWidth, framebufferHeight);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glUseProgram(program_);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glUniform1i(glGetUniformLocation(program_, "frame"), 0);
    glBindVertexArray(vertexArray_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

Image FrameDisplay::ReadBack(int width, int height) {
    std::vector<unsigned char> bytes(size_t(width) * height * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, bytes.data());
    Image image{uint32_t(width), uint32_t(height)};
    for (int y = 0; y < height; ++y)  // GL's rows run bottom to top
        for (int x = 0; x < width; ++x) {
            const unsigned char* p = &bytes[(size_t(height - 1 - y) * width + x) * 3];
            image.At(x, y) = vec3(p[0], p[1], p[2]) / 255.0f;
        }
    return image;
}

}  // namespace rtrt
