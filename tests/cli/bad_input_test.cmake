# Runs rtrt on bad input: each case must exit with status 2, print one message naming the file,
# field and reason, and leave no output image behind.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
file(WRITE ${WORK_DIR}/malformed.json "{ \"instances\": [ ")
file(WRITE ${WORK_DIR}/unknown_field.json "{ \"instances\": [], \"camera\": { \"fovy\": 45 } }")
file(WRITE ${WORK_DIR}/nan_mesh.obj "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n")
file(WRITE ${WORK_DIR}/nan_mesh.json
    "{ \"models\": { \"m\": { \"type\": \"mesh\", \"file\": \"nan_mesh.obj\" } }, \"instances\": [ { \"model\": \"m\" } ] }")
file(WRITE ${WORK_DIR}/no_triangles.obj "v 0 0 0\n")
file(WRITE ${WORK_DIR}/no_triangles.json
    "{ \"models\": { \"m\": { \"type\": \"mesh\", \"file\": \"no_triangles.obj\" } }, \"instances\": [ { \"model\": \"m\" } ] }")

function(expect_failure name expected_status expected_text)
    set(out ${WORK_DIR}/${name}.png)
    execute_process(COMMAND ${RTRT} ${ARGN} -o ${out}
        RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
    if(NOT status EQUAL ${expected_status})
        message(FATAL_ERROR "${name}: exit status ${status}, expected ${expected_status}\n${stderr}")
    endif()
    string(FIND "${stderr}" "${expected_text}" found)
    if(found EQUAL -1)
        message(FATAL_ERROR "${name}: message lacks \"${expected_text}\":\n${stderr}")
    endif()
    if(EXISTS ${out})
        message(FATAL_ERROR "${name}: wrote ${out} although it failed")
    endif()
    message(STATUS "${name}: ok (${stderr})")
endfunction()

expect_failure(missing_file 2 "nowhere.json: no such file" render ${WORK_DIR}/nowhere.json)
expect_failure(malformed 2 "malformed.json: malformed JSON" render ${WORK_DIR}/malformed.json)
expect_failure(unknown_field 2 "unknown_field.json: camera.fovy: unknown field" render ${WORK_DIR}/unknown_field.json)
expect_failure(nan_mesh 2 "nan_mesh.obj" render ${WORK_DIR}/nan_mesh.json)
expect_failure(no_triangles 2 "no_triangles.obj" render ${WORK_DIR}/no_triangles.json)
expect_failure(bad_size 2 "--size: width and height must be between 1 and 16384" render default --size 0x100)
expect_failure(mistyped_size 2 "expected WIDTHxHEIGHT" render default --size big)
expect_failure(bad_view 2 "--view" render default --view fancy)

# A bad output path fails before any rendering, and --help succeeds.
execute_process(COMMAND ${RTRT} render default -o ${WORK_DIR}/no/such/dir/out.png RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 2 OR NOT stderr MATCHES "does not exist")
    message(FATAL_ERROR "bad output folder: status ${status}: ${stderr}")
endif()
execute_process(COMMAND ${RTRT} render --help RESULT_VARIABLE status OUTPUT_VARIABLE stdout)
if(NOT status EQUAL 0 OR NOT stdout MATCHES "--max-depth")
    message(FATAL_ERROR "render --help: status ${status}")
endif()

# rtrt play: bad invocations exit 2 and write nothing; a good one writes every frame.
foreach(args "play;${SOURCE_DIR}/assets/scenes/demo_glass.json;${SOURCE_DIR}/assets/scenes/demo_glass.json;--headless;--frames;2;-o;${WORK_DIR}/f_%02d.png"
             "play;${SOURCE_DIR}/assets/scenes/demo_glass.json;--headless;--frames;2;-o;${WORK_DIR}/f.png"
             "play;${SOURCE_DIR}/assets/scenes/demo_glass.json;--headless;-o;${WORK_DIR}/f_%02d.png")
    execute_process(COMMAND ${RTRT} ${args} RESULT_VARIABLE status ERROR_VARIABLE stderr)
    file(GLOB written ${WORK_DIR}/f*.png)
    if(NOT status EQUAL 2 OR written)
        message(FATAL_ERROR "${args}: status ${status}, files ${written}: ${stderr}")
    endif()
endforeach()
# No display: the window cannot open; rtrt says so and points to --headless (exit 1; 2 in a
# build without the window).
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=DISPLAY --unset=WAYLAND_DISPLAY
    ${RTRT} play ${SOURCE_DIR}/assets/scenes/demo_glass.json --frames 2
    RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(status EQUAL 0 OR NOT stderr MATCHES "--headless")
    message(FATAL_ERROR "play without a display: status ${status}: ${stderr}")
endif()
execute_process(COMMAND ${RTRT} play ${SOURCE_DIR}/assets/scenes/demo_glass.json --headless --frames 3
    --size 64x36 -o ${WORK_DIR}/frame_%04d.png RESULT_VARIABLE status ERROR_VARIABLE stderr)
foreach(i 0000 0001 0002)
    if(NOT status EQUAL 0 OR NOT EXISTS ${WORK_DIR}/frame_${i}.png)
        message(FATAL_ERROR "play: status ${status}, frame ${i} missing: ${stderr}")
    endif()
endforeach()

# rtrt play is deterministic: two runs of the physics demo give byte-identical frames.
foreach(run a b)
    file(MAKE_DIRECTORY ${WORK_DIR}/${run})
    execute_process(COMMAND ${RTRT} play ${SOURCE_DIR}/assets/scenes/demo_physics.json --headless
        --frames 20 --size 64x36 -o ${WORK_DIR}/${run}/f_%02d.ppm RESULT_VARIABLE status ERROR_VARIABLE stderr)
    if(NOT status EQUAL 0)
        message(FATAL_ERROR "play run ${run}: status ${status}: ${stderr}")
    endif()
endforeach()
foreach(i RANGE 0 19)
    string(LENGTH "${i}" digits)
    set(name ${i})
    if(digits EQUAL 1)
        set(name 0${i})
    endif()
    file(SHA256 ${WORK_DIR}/a/f_${name}.ppm hash_a)
    file(SHA256 ${WORK_DIR}/b/f_${name}.ppm hash_b)
    if(NOT hash_a STREQUAL hash_b)
        message(FATAL_ERROR "play frame ${name} differs between two runs")
    endif()
endforeach()
file(SHA256 ${WORK_DIR}/a/f_00.ppm first)
file(SHA256 ${WORK_DIR}/a/f_19.ppm last)
if(first STREQUAL last)
    message(FATAL_ERROR "play: the physics demo did not move in 20 frames")
endif()
