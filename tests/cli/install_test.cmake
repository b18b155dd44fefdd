# An installed rtrt stands alone: installed to a temporary prefix and run from another folder,
# with no RTRT_MODEL_DIR and a user data folder of its own, it renders and plays its installed
# scenes by name; a missing model is named with its scene file, field, folder and the way to get
# it; `rtrt fetch-models` is there. The build tree stays on disk, but the installed program must
# not look at it: its scenes come from share/rtrt and its models from $XDG_DATA_HOME/rtrt/models.
# Built with OpenImageIO, it writes a PNG through its installed image library (lib/rtrt), which the
# program does not link; without that library only the images that need it fail, and say why.
# -DBUILD_DIR= -DWORK_DIR= -DMODEL_DIR= (the fetched models; the half that needs them skips
# without) -DWITH_OIIO=ON|OFF.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/elsewhere ${WORK_DIR}/data/rtrt)
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
    RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE stderr)
if(NOT status EQUAL 0)
    message(FATAL_ERROR "cmake --install: status ${status}: ${stderr}")
endif()
set(RTRT ${WORK_DIR}/prefix/bin/rtrt)
unset(ENV{RTRT_MODEL_DIR})
unset(ENV{RTRT_ASSET_DIR})
unset(ENV{RTRT_CACHE_DIR})
set(ENV{XDG_DATA_HOME} ${WORK_DIR}/data)
set(ENV{HOME} ${WORK_DIR})

function(run expected_status)
    execute_process(COMMAND ${RTRT} ${ARGN} WORKING_DIRECTORY ${WORK_DIR}/elsewhere
        RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
    if(NOT status EQUAL expected_status)
        message(FATAL_ERROR "rtrt ${ARGN}: status ${status} (expected ${expected_status}): "
            "${stdout}${stderr}")
    endif()
    set(stderr "${stderr}" PARENT_SCOPE)
endfunction()

# The installed rtrt starts wherever the build tree's does, without the dynamic linker's cache
# (where the CUDA toolkit's folder is registered on this machine, but need not be elsewhere): the
# install kept the run path to libcudart.
set(loader /lib64/ld-linux-x86-64.so.2)
if(EXISTS ${loader})
    execute_process(COMMAND ${loader} --inhibit-cache ${BUILD_DIR}/game/rtrt --version
        RESULT_VARIABLE built OUTPUT_QUIET ERROR_QUIET)
    execute_process(COMMAND ${loader} --inhibit-cache ${RTRT} --version
        RESULT_VARIABLE installed OUTPUT_QUIET ERROR_VARIABLE stderr)
    if(built EQUAL 0 AND NOT installed EQUAL 0)
        message(FATAL_ERROR "the installed rtrt does not start without ld.so.cache: ${stderr}")
    endif()
endif()

# A scene without fetched models, by name, from the installed scenes.
run(0 render reflective_sphere -o sphere.ppm --size 32x18 --backend cpu)
if(NOT EXISTS ${WORK_DIR}/elsewhere/sphere.ppm)
    message(FATAL_ERROR "render reflective_sphere wrote no image")
endif()
# A name that is no scene lists the ones there are.
run(2 render nosuch -o x.ppm)
if(NOT stderr MATCHES "nosuch: no such file \\(scenes by name: .*teapot_shadow.*; glTF models: .*walker")
    message(FATAL_ERROR "unexpected message for an unknown scene: ${stderr}")
endif()
# rtrt's own glTF models by name, from the installed share/rtrt/models.
run(0 info walker)
# No models in the data folder: the scene, the field, the folder and the way out.
run(2 render teapot_shadow -o teapot.ppm --size 32x18 --backend cpu)
set(models ${WORK_DIR}/data/rtrt/models)
if(NOT stderr MATCHES "teapot_shadow.json: models.teapot.file: @models/teapot.inc not found in ${models} \\(run rtrt fetch-models, or set RTRT_MODEL_DIR\\)")
    message(FATAL_ERROR "unexpected message for a missing model: ${stderr}")
endif()
run(0 fetch-models --help)
if(EXISTS ${MODEL_DIR}/teapot.inc)
    file(CREATE_LINK ${MODEL_DIR} ${models} SYMBOLIC)
    run(0 play teapot_shadow --headless --frames 2 --size 32x18 --backend cpu -o f_%02d.ppm)
    if(NOT EXISTS ${WORK_DIR}/elsewhere/f_01.ppm)
        message(FATAL_ERROR "play teapot_shadow wrote no frames")
    endif()
else()
    message(STATUS "the half with models skipped: no fetched teapot.inc in ${MODEL_DIR}")
endif()

if(NOT WITH_OIIO)
    return()
endif()
# The image library is the installed one, loaded when an image needs it: the program does not
# link OpenImageIO.
execute_process(COMMAND ldd ${RTRT} RESULT_VARIABLE status OUTPUT_VARIABLE libraries
    ERROR_VARIABLE libraries)
if(NOT status EQUAL 0 OR libraries MATCHES "OpenImageIO")
    message(FATAL_ERROR "ldd ${RTRT}: status ${status}; it must not link OpenImageIO:\n${libraries}")
endif()
run(0 render reflective_sphere -o sphere.png --size 32x18 --backend cpu)
file(READ ${WORK_DIR}/elsewhere/sphere.png signature LIMIT 8 HEX)
if(NOT signature STREQUAL "89504e470d0a1a0a")
    message(FATAL_ERROR "render reflective_sphere -o sphere.png wrote no PNG (${signature})")
endif()
# An installation without its image library: exit 1, naming the image that needed it and the
# loader's reason, no output; whatever needs no such image still runs.
set(library ${WORK_DIR}/prefix/lib/rtrt/rtrt_image_oiio.so)
if(NOT EXISTS ${library})
    message(FATAL_ERROR "cmake --install put no image library at ${library}")
endif()
file(RENAME ${library} ${library}.away)
run(1 render reflective_sphere -o broken.png --size 32x18 --backend cpu)
if(NOT stderr MATCHES "^rtrt: error: broken.png: cannot load the image library \\([^\n]*rtrt_image_oiio.so: cannot open shared object file: No such file or directory\\); reinstall rtrt\n$")
    message(FATAL_ERROR "unexpected message without the image library: ${stderr}")
endif()
if(EXISTS ${WORK_DIR}/elsewhere/broken.png)
    message(FATAL_ERROR "render wrote broken.png without the image library")
endif()
set(scenes ${WORK_DIR}/prefix/share/rtrt/scenes)
run(1 info ${scenes}/gltf_demo.json)
if(NOT stderr MATCHES "textured_quads.gltf: cannot load the image library \\(")
    message(FATAL_ERROR "unexpected message for glTF textures without the image library: ${stderr}")
endif()
run(0 --version)
run(0 info ${scenes}/demo_glass.json)
run(0 render reflective_sphere -o sphere2.ppm --size 32x18 --backend cpu)
file(RENAME ${library}.away ${library})
