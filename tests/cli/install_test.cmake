# An installed rtrt stands alone: installed to a temporary prefix and run from another folder,
# with no RTRT_MODEL_DIR and a user data folder of its own, it renders and plays its installed
# scenes by name; a missing model is named with its scene file, field, folder and the way to get
# it; `rtrt fetch-models` is there. The build tree stays on disk, but the installed program must
# not look at it: its scenes come from share/rtrt and its models from $XDG_DATA_HOME/rtrt/models.
# -DBUILD_DIR= -DWORK_DIR= -DMODEL_DIR= (the fetched models; the half that needs them skips
# without).
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

# A scene without fetched models, by name, from the installed scenes.
run(0 render reflective_sphere -o sphere.ppm --size 32x18 --backend cpu)
if(NOT EXISTS ${WORK_DIR}/elsewhere/sphere.ppm)
    message(FATAL_ERROR "render reflective_sphere wrote no image")
endif()
# A name that is no scene lists the ones there are.
run(2 render nosuch -o x.ppm)
if(NOT stderr MATCHES "nosuch: no such file \\(scenes by name: .*teapot_shadow")
    message(FATAL_ERROR "unexpected message for an unknown scene: ${stderr}")
endif()
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
