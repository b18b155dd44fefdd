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
# Draco (libdraco-dev) decodes KHR_draco_mesh_compression primitives; without it such files are
# refused with a message. Debian's libdraco.a bundles a tinygltf and stb of its own
# (tiny_gltf_utils.cc.o): GNU ld extracts that member for libtinygltf.so's stb references even
# after libstb, and its tinygltf then replaces Debian's (every glTF load fails). rtrt links a copy
# of the archive without that member (the decoder does not use it), statically, so that the
# binary needs nothing more at run time.
set(RTRT_DRACO "AUTO" CACHE STRING "Decode Draco-compressed glTF meshes: AUTO (when found), ON, OFF")
if(NOT RTRT_DRACO STREQUAL "OFF")
    find_package(draco CONFIG QUIET)
    if(TARGET draco::draco_static)
        foreach(config NONE RELEASE NOCONFIG)
            get_target_property(draco_archive draco::draco_static IMPORTED_LOCATION_${config})
            if(draco_archive)
                break()
            endif()
        endforeach()
        get_target_property(draco_include draco::draco_static INTERFACE_INCLUDE_DIRECTORIES)
        set(draco_decoder "${CMAKE_BINARY_DIR}/draco/libdraco_decoder.a")
        file(MAKE_DIRECTORY "${CMAKE_BINARY_DIR}/draco")
        file(COPY_FILE "${draco_archive}" "${draco_decoder}" ONLY_IF_DIFFERENT)
        execute_process(COMMAND "${CMAKE_AR}" d "${draco_decoder}" tiny_gltf_utils.cc.o
                        RESULT_VARIABLE draco_ar)
        if(draco_ar EQUAL 0)
            add_library(rtrt_draco STATIC IMPORTED GLOBAL)
            set_target_properties(rtrt_draco PROPERTIES IMPORTED_LOCATION "${draco_decoder}"
                INTERFACE_INCLUDE_DIRECTORIES "${draco_include}")
            set(RTRT_WITH_DRACO ON)
        endif()
    endif()
    if(NOT RTRT_WITH_DRACO AND RTRT_DRACO STREQUAL "ON")
        message(FATAL_ERROR "RTRT_DRACO=ON needs libdraco-dev")
    endif()
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
