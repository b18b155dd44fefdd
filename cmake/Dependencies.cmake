# Every dependency is a Debian package (../shared/BUILD_NOTES.md says how each one behaves).
find_package(glm REQUIRED)
find_package(TBB REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json REQUIRED)
find_package(ZLIB REQUIRED)
# tinygltf is Debian's shared library (its implementation and stb's are inside it): glTF import.
find_package(TinyGLTF REQUIRED)
# xxHash (libxxhash-dev) is used header-only (XXH_INLINE_ALL): no library to link.
find_path(XXHASH_INCLUDE_DIR xxhash.h REQUIRED)
find_package(PkgConfig REQUIRED)
if(RTRT_WITH_OIIO)
    # Debian's OpenImageIOConfig.cmake names a missing opencv4 include dir; pkg-config works.
    pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
endif()
if(RTRT_BUILD_TESTS)
    find_package(GTest REQUIRED)
endif()

# The interactive window: GLFW 3.3, OpenGL through GLVND (libOpenGL + libGLX) and Dear ImGui, whose
# Debian static library already holds its GLFW and OpenGL 3 back ends.
if(NOT RTRT_WINDOW STREQUAL "OFF")
    find_package(glfw3 3.3 QUIET)
    set(OpenGL_GL_PREFERENCE GLVND)
    find_package(OpenGL QUIET COMPONENTS OpenGL GLX)
    pkg_check_modules(IMGUI QUIET IMPORTED_TARGET imgui)
    if(glfw3_FOUND AND OpenGL_OpenGL_FOUND AND IMGUI_FOUND)
        set(RTRT_HAVE_WINDOW ON)
    elseif(RTRT_WINDOW STREQUAL "ON")
        message(FATAL_ERROR "RTRT_WINDOW=ON needs libglfw3-dev, libgl-dev and libimgui-dev")
    endif()
endif()
