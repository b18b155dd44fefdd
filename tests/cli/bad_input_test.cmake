# Runs rtrt on bad input: each case must exit with status 2, print one message naming the file,
# field and reason, and leave no output image behind.
file(REMOVE_RECURSE ${WORK_DIR})
get_filename_component(WORK_DIR_NAME ${WORK_DIR} NAME)
file(MAKE_DIRECTORY ${WORK_DIR})
file(WRITE ${WORK_DIR}/malformed.json "{ \"instances\": [ ")
file(WRITE ${WORK_DIR}/unknown_field.json "{ \"instances\": [], \"camera\": { \"fovy\": 45 } }")
file(WRITE ${WORK_DIR}/nan_mesh.obj "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n")
file(WRITE ${WORK_DIR}/nan_mesh.json
    "{ \"models\": { \"m\": { \"type\": \"mesh\", \"file\": \"nan_mesh.obj\" } }, \"instances\": [ { \"model\": \"m\" } ] }")
file(WRITE ${WORK_DIR}/no_triangles.obj "v 0 0 0\n")
file(WRITE ${WORK_DIR}/no_triangles.json
    "{ \"models\": { \"m\": { \"type\": \"mesh\", \"file\": \"no_triangles.obj\" } }, \"instances\": [ { \"model\": \"m\" } ] }")

# Images are written as PNG, or as PPM by a build without OpenImageIO (the GPU machine's).
if(NOT DEFINED EXT)
    set(EXT .png)
endif()

function(expect_failure name expected_status expected_text)
    set(out ${WORK_DIR}/${name}${EXT})
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
expect_failure(malformed 2 "malformed.json: line 1, column 18: malformed JSON: the text ends before the JSON does" render ${WORK_DIR}/malformed.json)
expect_failure(unknown_field 2 "unknown_field.json: camera.fovy: unknown field" render ${WORK_DIR}/unknown_field.json)
expect_failure(nan_mesh 2 "nan_mesh.obj" render ${WORK_DIR}/nan_mesh.json)
expect_failure(no_triangles 2 "no_triangles.obj" render ${WORK_DIR}/no_triangles.json)
expect_failure(bad_size 2 "--size: width and height must be between 1 and 16384" render default --size 0x100)
expect_failure(mistyped_size 2 "expected WIDTHxHEIGHT" render default --size big)
expect_failure(bad_view 2 "--view" render default --view fancy)
expect_failure(bad_spp 2 "--spp" render default --spp 3)
expect_failure(accuracy_bad_backend 2 "--backend" bench accuracy --backend gpu)
expect_failure(accuracy_bad_size 2 "--size: width and height must be between 1 and 16384" bench accuracy --size 0x100)
expect_failure(unknown_physics_solver 2 "--physics-solver" play default --headless --frames 1 --physics-solver quantum)
# CLI11's ranges let NaN through (both comparisons are false); rtrt's number options do not.
expect_failure(nan_exposure 2 "--exposure: nan is not a finite number" render default --exposure nan)
expect_failure(nan_fps 2 "--fps: nan is not a finite number" play default --headless --frames 1 --fps nan)

# --physics-solver gpu on a machine without a CUDA device: refused before any frame, saying what to
# use instead; a machine with one plays the frame. Which of the two this machine is comes from the
# CUDA back end itself (a render of 8x8 pixels): without a device only the refusal passes (exit 0
# passed anywhere before).
execute_process(COMMAND ${RTRT} render default --backend cuda --size 8x8
    -o ${WORK_DIR}/cuda_probe${EXT} RESULT_VARIABLE cuda_status OUTPUT_QUIET ERROR_QUIET)
execute_process(COMMAND ${RTRT} play ${SOURCE_DIR}/assets/scenes/demo_physics.json --headless
    --frames 1 --size 32x18 --physics-solver gpu -o ${WORK_DIR}/gpu_physics_%d${EXT}
    RESULT_VARIABLE status ERROR_VARIABLE stderr)
file(GLOB written ${WORK_DIR}/gpu_physics_*)
if(cuda_status EQUAL 0)
    if(NOT status EQUAL 0 OR NOT written)
        message(FATAL_ERROR "gpu_physics with a device: exit status ${status}, wrote '${written}'\n${stderr}")
    endif()
else()
    if(NOT status EQUAL 2 OR NOT stderr MATCHES "--physics-solver: gpu: cannot solve contacts on the GPU: .*; use --physics-solver cpu")
        message(FATAL_ERROR "gpu_physics_without_device: exit status ${status} (expected 2), message:\n${stderr}")
    endif()
    if(written)
        message(FATAL_ERROR "gpu_physics_without_device: wrote ${written} although it failed")
    endif()
endif()

# A bad output path fails before any rendering, and --help succeeds.
execute_process(COMMAND ${RTRT} render default -o ${WORK_DIR}/no/such/dir/out${EXT} RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 2 OR NOT stderr MATCHES "does not exist")
    message(FATAL_ERROR "bad output folder: status ${status}: ${stderr}")
endif()
execute_process(COMMAND ${RTRT} render --help RESULT_VARIABLE status OUTPUT_VARIABLE stdout)
if(NOT status EQUAL 0 OR NOT stdout MATCHES "--max-depth")
    message(FATAL_ERROR "render --help: status ${status}")
endif()
# An output that names an input (or another output) is refused before any work, the input intact.
file(COPY_FILE ${SOURCE_DIR}/assets/scenes/demo_glass.json ${WORK_DIR}/own_scene.json)
file(READ ${WORK_DIR}/own_scene.json scene_before)
execute_process(COMMAND ${RTRT} render ${WORK_DIR}/own_scene.json --size 8x8
    -o ${WORK_DIR}/../${WORK_DIR_NAME}/own_scene.json RESULT_VARIABLE status ERROR_VARIABLE stderr)
file(READ ${WORK_DIR}/own_scene.json scene_after)
if(NOT status EQUAL 2 OR NOT stderr MATCHES "is also the input file" OR
   NOT scene_before STREQUAL scene_after)
    message(FATAL_ERROR "render -o its own scene: status ${status}: ${stderr}")
endif()
execute_process(COMMAND ${RTRT} play ${WORK_DIR}/own_scene.json --headless --frames 1 --size 8x8
    -o ${WORK_DIR}/own_%02d${EXT} --manifest ${WORK_DIR}/own_scene.json
    RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 2 OR NOT stderr MATCHES "--manifest: .*is also the input file" OR
   EXISTS ${WORK_DIR}/own_00${EXT})
    message(FATAL_ERROR "play --manifest its own scene: status ${status}: ${stderr}")
endif()

# A scene with nothing to draw until its spawner's bodies come plays its empty frames (it crashed:
# the empty TLAS's cost recursed until the stack ran out).
file(WRITE ${WORK_DIR}/spawn_later.json [=[{ "models": { "b": { "type": "box" } }, "instances": [],
  "spawners": [ { "model": "b", "time": 0.02, "grid": { "count": [1, 1, 1] } } ] }]=])
execute_process(COMMAND ${RTRT} play ${WORK_DIR}/spawn_later.json --headless --backend cpu
    --frames 3 --size 8x8 -o ${WORK_DIR}/later_%d${EXT} RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 0 OR NOT EXISTS ${WORK_DIR}/later_2${EXT})
    message(FATAL_ERROR "play of a scene whose bodies spawn later: status ${status}: ${stderr}")
endif()

# Bad input found after the manifest's check leaves no empty manifest behind; a frame number in a
# folder's name is refused before any frame (frame 0 had been written, then frame 1 failed).
execute_process(COMMAND ${RTRT} play ${WORK_DIR}/own_scene.json --headless --frames 2 --size 0x9
    -o ${WORK_DIR}/m_%02d${EXT} --manifest ${WORK_DIR}/new_manifest.tsv
    RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 2 OR EXISTS ${WORK_DIR}/new_manifest.tsv)
    message(FATAL_ERROR "play with a bad --size left a manifest: status ${status}: ${stderr}")
endif()
file(MAKE_DIRECTORY ${WORK_DIR}/d_0000)
execute_process(COMMAND ${RTRT} play ${WORK_DIR}/own_scene.json --headless --frames 2 --size 8x8
    -o ${WORK_DIR}/d_%04d/frame${EXT} RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 2 OR NOT stderr MATCHES "the frame number must be in the file name" OR
   EXISTS ${WORK_DIR}/d_0000/frame${EXT})
    message(FATAL_ERROR "play -o DIR_%04d/frame: status ${status}: ${stderr}")
endif()

# --record with a video name rtrt does not record is refused before a window opens (it had become a
# folder of PNG frames named out.avi).
execute_process(COMMAND ${RTRT} play ${WORK_DIR}/own_scene.json --record ${WORK_DIR}/out.avi
    --frames 2 RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 2 OR EXISTS ${WORK_DIR}/out.avi OR NOT
   (stderr MATCHES "rtrt records .mp4, .mkv or .mov video" OR stderr MATCHES "without the window"))
    message(FATAL_ERROR "play --record out.avi: status ${status}: ${stderr}")
endif()

# What a command prints must arrive: stdout on a full device is a failure (exit 1), not exit 0 with
# the text lost.
if(EXISTS /dev/full)
    execute_process(COMMAND ${RTRT} info default OUTPUT_FILE /dev/full RESULT_VARIABLE status
        ERROR_VARIABLE stderr)
    if(NOT status EQUAL 1 OR NOT stderr MATCHES "rtrt: error: stdout: No space left on device")
        message(FATAL_ERROR "info > /dev/full: status ${status}: ${stderr}")
    endif()
    # A render whose image is written says that only its messages were lost.
    execute_process(COMMAND ${RTRT} render default --size 8x4 -o ${WORK_DIR}/printed${EXT}
        OUTPUT_FILE /dev/full RESULT_VARIABLE status ERROR_VARIABLE stderr)
    if(NOT status EQUAL 1 OR NOT EXISTS ${WORK_DIR}/printed${EXT} OR NOT stderr MATCHES
       "stdout: No space left on device \\(the command's work is done, any files it wrote are complete")
        message(FATAL_ERROR "render > /dev/full: status ${status}: ${stderr}")
    endif()
endif()

# rtrt play: bad invocations exit 2 and write nothing; a good one writes every frame.
foreach(args "play;${SOURCE_DIR}/assets/scenes/demo_glass.json;${SOURCE_DIR}/assets/scenes/demo_glass.json;--headless;--frames;2;-o;${WORK_DIR}/f_%02d${EXT}"
             "play;${SOURCE_DIR}/assets/scenes/demo_glass.json;--headless;--frames;2;-o;${WORK_DIR}/f${EXT}"
             "play;${SOURCE_DIR}/assets/scenes/demo_glass.json;--headless;-o;${WORK_DIR}/f_%02d${EXT}")
    execute_process(COMMAND ${RTRT} ${args} RESULT_VARIABLE status ERROR_VARIABLE stderr)
    file(GLOB written ${WORK_DIR}/f*${EXT})
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
    --size 64x36 -o ${WORK_DIR}/frame_%04d${EXT} RESULT_VARIABLE status ERROR_VARIABLE stderr)
foreach(i 0000 0001 0002)
    if(NOT status EQUAL 0 OR NOT EXISTS ${WORK_DIR}/frame_${i}${EXT})
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

# A range of frames, --frames A:B, is byte for byte what the full run wrote (the frames before
# A are replayed untraced).
file(MAKE_DIRECTORY ${WORK_DIR}/range)
execute_process(COMMAND ${RTRT} play ${SOURCE_DIR}/assets/scenes/demo_physics.json --headless
    --frames 12:20 --size 64x36 -o ${WORK_DIR}/range/f_%02d.ppm
    RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT status EQUAL 0 OR NOT stdout MATCHES "replayed frames 0 to 11 untraced")
    message(FATAL_ERROR "play --frames 12:20: status ${status}: ${stdout}${stderr}")
endif()
if(EXISTS ${WORK_DIR}/range/f_11.ppm)
    message(FATAL_ERROR "play --frames 12:20 wrote frame 11")
endif()
foreach(i RANGE 12 19)
    file(SHA256 ${WORK_DIR}/a/f_${i}.ppm hash_full)
    file(SHA256 ${WORK_DIR}/range/f_${i}.ppm hash_range)
    if(NOT hash_full STREQUAL hash_range)
        message(FATAL_ERROR "play --frames 12:20: frame ${i} differs from the full run's")
    endif()
endforeach()

# A skinned, animated glTF played headless: every frame differs from the one before (the mesh
# deforms, it is not frozen in its bind pose) and two runs give byte-identical frames.
foreach(run c d)
    file(MAKE_DIRECTORY ${WORK_DIR}/${run})
    execute_process(COMMAND ${RTRT} play ${SOURCE_DIR}/assets/models/walker.gltf --headless
        --frames 8 --size 48x64 --backend cpu -o ${WORK_DIR}/${run}/w_%02d.ppm
        RESULT_VARIABLE status ERROR_VARIABLE stderr)
    if(NOT status EQUAL 0)
        message(FATAL_ERROR "play walker run ${run}: status ${status}: ${stderr}")
    endif()
endforeach()
set(previous "")
foreach(i RANGE 0 7)
    file(SHA256 ${WORK_DIR}/c/w_0${i}.ppm hash_c)
    file(SHA256 ${WORK_DIR}/d/w_0${i}.ppm hash_d)
    if(NOT hash_c STREQUAL hash_d)
        message(FATAL_ERROR "play walker frame ${i} differs between two runs")
    endif()
    if(hash_c STREQUAL previous)
        message(FATAL_ERROR "play walker frame ${i} equals frame before it: the skin did not move")
    endif()
    set(previous ${hash_c})
endforeach()

# A frame named like a file the scene reads (a glTF file's texture) is refused before any frame
# is traced, not when that frame is written: play read the scene's files only after its checks.
# The texture is written by rtrt itself, so only where images are PNG.
if(EXT STREQUAL .png)
    execute_process(COMMAND ${RTRT} render default --size 8x8 -o ${WORK_DIR}/tex_0.png
        RESULT_VARIABLE status ERROR_VARIABLE stderr)
    file(READ ${SOURCE_DIR}/assets/models/textured_quads.gltf quads)
    string(REGEX REPLACE "data:image/png;base64,[A-Za-z0-9+/=]+" "tex_0.png" quads "${quads}")
    file(WRITE ${WORK_DIR}/quads.gltf "${quads}")
    file(SHA256 ${WORK_DIR}/tex_0.png texture_before)
    execute_process(COMMAND ${RTRT} play ${WORK_DIR}/quads.gltf --headless --frames 2
        --size 16x16 --backend cpu -o ${WORK_DIR}/tex_%d.png
        RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
    file(SHA256 ${WORK_DIR}/tex_0.png texture_after)
    string(FIND "${stderr}" "frame 0 would be written over a file of the scene" found)
    if(NOT status EQUAL 2 OR found EQUAL -1 OR EXISTS ${WORK_DIR}/tex_1.png
       OR NOT texture_before STREQUAL texture_after)
        message(FATAL_ERROR "play over a scene's texture: status ${status}\n${stdout}${stderr}")
    endif()
    message(STATUS "play over a scene's texture: ok (${stderr})")
endif()

# rtrt convert and rtrt info: bad input exits 2 with one "file: field: reason" line and writes
# nothing; good input converts, describes and renders.
set(HOSTILE ${SOURCE_DIR}/tests/data/hostile)
file(WRITE ${WORK_DIR}/tetra.obj "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n")
function(expect_bad_input name expected_text)
    set(out ${WORK_DIR}/out.rtmodel)
    execute_process(COMMAND ${RTRT} ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
    string(REGEX MATCHALL "\n" lines "${stderr}")
    list(LENGTH lines line_count)
    if(NOT status EQUAL 2 OR NOT line_count EQUAL 1)
        message(FATAL_ERROR "${name}: exit status ${status} (expected 2), ${line_count} lines:\n${stderr}")
    endif()
    string(FIND "${stderr}" "rtrt: error: ${expected_text}" found)
    if(found EQUAL -1)
        message(FATAL_ERROR "${name}: message lacks \"${expected_text}\":\n${stderr}")
    endif()
    file(GLOB written ${WORK_DIR}/out.rtmodel* ${WORK_DIR}/no)
    if(written)
        message(FATAL_ERROR "${name}: wrote ${written} although it failed")
    endif()
    message(STATUS "${name}: ok (${stderr})")
endfunction()

set(OUT ${WORK_DIR}/out.rtmodel)
expect_bad_input(convert_nan "${WORK_DIR}/nan_mesh.obj: line 3: vertex coordinate is NaN" convert ${WORK_DIR}/nan_mesh.obj -o ${OUT})
expect_bad_input(convert_missing "${WORK_DIR}/none.obj: no such file" convert ${WORK_DIR}/none.obj -o ${OUT})
expect_bad_input(convert_no_triangles "${WORK_DIR}/no_triangles.obj" convert ${WORK_DIR}/no_triangles.obj -o ${OUT})
expect_bad_input(convert_not_rtmodel "--output: expected a file name ending in .rtmodel" convert ${WORK_DIR}/tetra.obj -o ${WORK_DIR}/out.png)
expect_bad_input(convert_no_folder "--output: folder ${WORK_DIR}/no/such does not exist" convert ${WORK_DIR}/tetra.obj -o ${WORK_DIR}/no/such/out.rtmodel)
expect_bad_input(convert_rtmodel "${HOSTILE}/valid.rtmodel: is already an .rtmodel" convert ${HOSTILE}/valid.rtmodel -o ${OUT})
foreach(case "empty|header: truncated"
             "truncated_payload|header.fileBytes: the counts give"
             "wrong_magic|header.magic: not an .rtmodel file"
             "wrong_version|header.version: version 99"
             "huge_count|header.counts.triangles: 1152921504606846976 elements cannot fit"
             "bad_payload_checksum|payloadChecksum: checksum mismatch"
             "child_out_of_range|nodes[0].leftFirst: child index 1000000 out of range"
             "nan_vertex|triangles[3]: vertex coordinate is NaN or infinite"
             "prim_id_out_of_range|primIds[5]: primitive index 1000000 out of range")
    string(REPLACE "|" ";" parts "${case}")
    list(GET parts 0 name)
    list(GET parts 1 text)
    expect_bad_input(info_${name} "${HOSTILE}/${name}.rtmodel: ${text}" info ${HOSTILE}/${name}.rtmodel)
endforeach()
expect_bad_input(info_missing "${WORK_DIR}/none.rtmodel: no such file" info ${WORK_DIR}/none.rtmodel)
# A --dir that cannot be made is refused before the script runs (it had failed the fetch, exit 1).
expect_bad_input(fetch_models_dir_under_a_file "--dir: ${WORK_DIR}/tetra.obj/models: cannot create the folder" fetch-models --dir ${WORK_DIR}/tetra.obj/models)
file(WRITE ${WORK_DIR}/hostile_scene.json
    "{ \"models\": { \"m\": { \"type\": \"mesh\", \"file\": \"${HOSTILE}/nan_vertex.rtmodel\" } }, \"instances\": [ { \"model\": \"m\" } ] }")
expect_failure(render_hostile_rtmodel 2 "nan_vertex.rtmodel: triangles[3]" render ${WORK_DIR}/hostile_scene.json)

foreach(command convert info)
    execute_process(COMMAND ${RTRT} ${command} --help RESULT_VARIABLE status OUTPUT_VARIABLE stdout)
    if(NOT status EQUAL 0 OR NOT stdout MATCHES "rtmodel")
        message(FATAL_ERROR "${command} --help: status ${status}: ${stdout}")
    endif()
endforeach()

execute_process(COMMAND ${RTRT} convert ${WORK_DIR}/tetra.obj -o ${WORK_DIR}/tetra.rtmodel --builder sweep
    RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT status EQUAL 0 OR NOT stdout MATCHES "SAH cost [0-9.]+" OR NOT stdout MATCHES "parse [0-9.]+ ms, build"
   OR NOT EXISTS ${WORK_DIR}/tetra.rtmodel)
    message(FATAL_ERROR "convert: status ${status}: ${stdout}${stderr}")
endif()
execute_process(COMMAND ${RTRT} info ${WORK_DIR}/tetra.rtmodel RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT status EQUAL 0 OR NOT stdout MATCHES "triangles +4\n" OR NOT stdout MATCHES "vertices +4 "
   OR NOT stdout MATCHES "built by +sweep builder \\(leaves up to [0-9]+\\) from" OR NOT stdout MATCHES "SAH cost")
    message(FATAL_ERROR "info tetra.rtmodel: status ${status}: ${stdout}${stderr}")
endif()
file(WRITE ${WORK_DIR}/tetra_scene.json
    "{ \"materials\": { \"red\": { \"diffuse\": [0.8, 0.1, 0.1] } }, \"lights\": [ { \"type\": \"point\", \"position\": [3, 4, 3] } ], \"models\": { \"t\": { \"type\": \"mesh\", \"file\": \"tetra.rtmodel\", \"fit\": 2 } }, \"instances\": [ { \"model\": \"t\", \"material\": \"red\" } ] }")
execute_process(COMMAND ${RTRT} info ${WORK_DIR}/tetra_scene.json RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT status EQUAL 0 OR NOT stdout MATCHES "materials +1: red" OR NOT stdout MATCHES "point at"
   OR NOT stdout MATCHES "- t: 4 triangles")
    message(FATAL_ERROR "info tetra_scene.json: status ${status}: ${stdout}${stderr}")
endif()
execute_process(COMMAND ${RTRT} render ${WORK_DIR}/tetra_scene.json --size 32x18 -o ${WORK_DIR}/tetra.ppm
    RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 0 OR NOT EXISTS ${WORK_DIR}/tetra.ppm)
    message(FATAL_ERROR "render tetra_scene.json: status ${status}: ${stderr}")
endif()

# glTF and scene files from the hostile corpora: render and info exit 2 with exactly one
# "file: field: reason" line (no warning before it) and write nothing.
set(HOSTILE_GLTF ${SOURCE_DIR}/tests/data/hostile_gltf)
set(HOSTILE_SCENE ${SOURCE_DIR}/tests/data/hostile_scene)
function(expect_one_line_failure name expected_text)
    set(out ${WORK_DIR}/${name}${EXT})
    execute_process(COMMAND ${RTRT} ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
    string(REGEX MATCHALL "\n" lines "${stderr}")
    list(LENGTH lines line_count)
    if(NOT status EQUAL 2 OR NOT line_count EQUAL 1)
        message(FATAL_ERROR "${name}: exit status ${status} (expected 2), ${line_count} lines:\n${stderr}")
    endif()
    string(FIND "${stderr}" "rtrt: error: ${expected_text}" found)
    if(found EQUAL -1)
        message(FATAL_ERROR "${name}: message lacks \"${expected_text}\":\n${stderr}")
    endif()
    if(EXISTS ${out})
        message(FATAL_ERROR "${name}: wrote ${out} although it failed")
    endif()
    message(STATUS "${name}: ok (${stderr})")
endfunction()
foreach(case "truncated.glb|header.length: the header says"
             "wrong_magic.glb|header.magic: not a GLB file"
             "wrong_version.glb|header.version: GLB version 1"
             "huge_count.gltf|accessors[0].count: 1000000000 elements"
             "nan_position.glb|meshes[0].primitives[0].attributes.POSITION: accessor 0, element 1: NaN"
             "inf_translation.gltf|nodes[1].translation: a value is NaN or infinite"
             "index_out_of_range.gltf|meshes[0].primitives[0].indices: index 2 is 7"
             "cycle_without_root.gltf|nodes[2].children: node 2 is its own ancestor"
             "missing_buffer.gltf|buffers[0].uri: no such file"
             "missing_image.gltf|images[0].uri: no such file"
             "wrong_json_type.gltf|nodes[1].translation: expected an array of 3 numbers")
    string(REPLACE "|" ";" parts "${case}")
    list(GET parts 0 name)
    list(GET parts 1 text)
    string(REPLACE "." "_" id ${name})
    expect_one_line_failure(render_${id} "${HOSTILE_GLTF}/${name}: ${text}"
        render ${HOSTILE_GLTF}/${name} -o ${WORK_DIR}/render_${id}${EXT})
    expect_one_line_failure(info_${id} "${HOSTILE_GLTF}/${name}: ${text}" info ${HOSTILE_GLTF}/${name})
endforeach()
# A frame number field wider than two digits would name files longer than file systems allow.
expect_one_line_failure(wide_frame_field
    "--output: expected a pattern with one frame number field of at most two digits' width"
    play default --headless --frames 1 -o ${WORK_DIR}/g_%300d.png)
# A literal % and a tab (which would split the manifest's lines) in the pattern.
expect_one_line_failure(percent_in_pattern "--output: ${WORK_DIR}/percent_%%_%d.png: a % of its own (%%)"
    play default --headless --frames 1 -o ${WORK_DIR}/percent_%%_%d.png)
expect_one_line_failure(tab_in_pattern "--output: the pattern has a control character"
    play default --headless --frames 1 -o "${WORK_DIR}/tabbed\t_%d.png")
# Exposure and tone map apply to linear colours; the default scene's are display values.
expect_one_line_failure(display_exposure
    "--exposure: 1: applies to linear colours, and this scene's are display values"
    render default --exposure 1 -o ${WORK_DIR}/display_exposure${EXT})
expect_one_line_failure(display_tone_map
    "--tone-map: aces: applies to linear colours, and this scene's are display values"
    play default --headless --frames 1 --tone-map aces -o ${WORK_DIR}/dt_%d.png)
# Options of the window given headless, or the other way round, would do nothing: refused.
expect_one_line_failure(headless_record "--record: records the window"
    play default --headless --frames 1 --record ${WORK_DIR}/r.mp4 -o ${WORK_DIR}/hr_%d.png)
expect_one_line_failure(window_manifest "--manifest: is for --headless frames"
    play default --manifest ${WORK_DIR}/m.txt)
# --spp 1 too: given, it is refused as any other value (it was let through as the default).
expect_one_line_failure(window_spp "--spp: is for --headless frames"
    play default --spp 1)
# Their outputs are patterns and other files, not the NAME.EXT expect_one_line_failure looks for.
file(GLOB left ${WORK_DIR}/g_* ${WORK_DIR}/hr_* ${WORK_DIR}/r.mp4 ${WORK_DIR}/m.txt
    ${WORK_DIR}/percent_* ${WORK_DIR}/tabbed* ${WORK_DIR}/dt_*)
if(left)
    message(FATAL_ERROR "refused play options wrote ${left}")
endif()
expect_one_line_failure(render_hostile_gltf_model
    "${HOSTILE_SCENE}/../hostile_gltf/cyclic_nodes.gltf: nodes[2].children[0]: node 1 has two parents"
    render ${HOSTILE_SCENE}/hostile_gltf_model.json -o ${WORK_DIR}/render_hostile_gltf_model${EXT})
expect_one_line_failure(render_gltf_spawner "${HOSTILE_SCENE}/gltf_spawner.json: spawners[0].rain"
    render ${HOSTILE_SCENE}/gltf_spawner.json -o ${WORK_DIR}/render_gltf_spawner${EXT})

# A valid glTF renders directly, and info describes it.
execute_process(COMMAND ${RTRT} render ${HOSTILE_GLTF}/valid.glb --size 32x18 -o ${WORK_DIR}/valid_glb.ppm
    RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 0 OR NOT EXISTS ${WORK_DIR}/valid_glb.ppm)
    message(FATAL_ERROR "render valid.glb: status ${status}: ${stderr}")
endif()
execute_process(COMMAND ${RTRT} info ${HOSTILE_GLTF}/valid.gltf RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT status EQUAL 0 OR NOT stdout MATCHES "glTF 2.0 scene" OR NOT stdout MATCHES "nodes +2 in the scene"
   OR NOT stdout MATCHES "1 triangles, 3 vertices" OR NOT stdout MATCHES "SAH cost")
    message(FATAL_ERROR "info valid.gltf: status ${status}: ${stdout}${stderr}")
endif()

# The committed textured glTF plays headless (its animation moves the quads) and info lists it.
set(QUADS ${SOURCE_DIR}/assets/models/textured_quads.gltf)
execute_process(COMMAND ${RTRT} play ${QUADS} --headless --frames 2 --fps 1 --size 48x32
    -o ${WORK_DIR}/quads_%02d.ppm RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 0 OR NOT EXISTS ${WORK_DIR}/quads_00.ppm OR NOT EXISTS ${WORK_DIR}/quads_01.ppm)
    message(FATAL_ERROR "play textured_quads.gltf: status ${status}: ${stderr}")
endif()
file(SHA256 ${WORK_DIR}/quads_00.ppm first)
file(SHA256 ${WORK_DIR}/quads_01.ppm second)
if(first STREQUAL second)
    message(FATAL_ERROR "play textured_quads.gltf: the glTF animation did not move anything")
endif()
execute_process(COMMAND ${RTRT} info ${QUADS} RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT status EQUAL 0 OR NOT stdout MATCHES "materials   4, textures 3"
   OR NOT stdout MATCHES "animations  1 \\(the first plays: 2 nodes, 2 s, looping\\)"
   OR NOT stdout MATCHES "cameras     1 placed, lights 2 placed")
    message(FATAL_ERROR "info textured_quads.gltf: status ${status}: ${stdout}${stderr}")
endif()

# A mistyped command is named, with the nearest command (exit 2).
execute_process(COMMAND ${RTRT} rendr default RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 2 OR NOT stderr MATCHES "'rendr' is not an rtrt command; did you mean 'render'\\?")
    message(FATAL_ERROR "rtrt rendr: status ${status}: ${stderr}")
endif()
# So is a mistyped subcommand, and an option where a command is expected (CLI11 said only "A
# subcommand is required").
execute_process(COMMAND ${RTRT} bench cpuu RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 2 OR NOT stderr MATCHES "'cpuu' is not a 'rtrt bench' command; did you mean 'cpu'\\?.*rtrt bench --help")
    message(FATAL_ERROR "rtrt bench cpuu: status ${status}: ${stderr}")
endif()
execute_process(COMMAND ${RTRT} --bogus RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 2 OR NOT stderr MATCHES "'--bogus' is not an option of rtrt \\(rtrt --help\\)")
    message(FATAL_ERROR "rtrt --bogus: status ${status}: ${stderr}")
endif()
# rtrt play with no scene plays the built-in one (the same first frame as render default), and
# its progress into a log is lines, not carriage returns.
execute_process(COMMAND ${RTRT} play --headless --frames 2 --size 32x18 --backend cpu
    -o ${WORK_DIR}/default_%02d${EXT} RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 0 OR NOT EXISTS ${WORK_DIR}/default_01${EXT})
    message(FATAL_ERROR "play with no scene: status ${status}: ${stderr}")
endif()
string(FIND "${stderr}" "\r" carriage)
if(NOT carriage EQUAL -1 OR NOT stderr MATCHES "rtrt play: 2/2 frames")
    message(FATAL_ERROR "play progress into a log: ${stderr}")
endif()
execute_process(COMMAND ${RTRT} render default --size 32x18 -o ${WORK_DIR}/default_render${EXT}
    RESULT_VARIABLE status)
file(SHA256 ${WORK_DIR}/default_00${EXT} played)
file(SHA256 ${WORK_DIR}/default_render${EXT} rendered)
if(NOT status EQUAL 0 OR NOT played STREQUAL rendered)
    message(FATAL_ERROR "play default's first frame differs from render default")
endif()

# The output is checked before any work: -o naming a folder, or a folder rtrt may not write into
# (checked where the test runs as an ordinary user: root may write anywhere), is bad input.
file(MAKE_DIRECTORY ${WORK_DIR}/out_folder${EXT})
execute_process(COMMAND ${RTRT} render ${WORK_DIR}/nowhere.json -o ${WORK_DIR}/out_folder${EXT}
    RESULT_VARIABLE status ERROR_VARIABLE stderr)
if(NOT status EQUAL 2 OR NOT stderr MATCHES "out_folder${EXT}: is a folder; name an image file")
    message(FATAL_ERROR "-o naming a folder: status ${status}: ${stderr}")
endif()
execute_process(COMMAND id -u OUTPUT_VARIABLE uid OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT uid STREQUAL "0")
    file(MAKE_DIRECTORY ${WORK_DIR}/read_only)
    file(CHMOD ${WORK_DIR}/read_only DIRECTORY_PERMISSIONS OWNER_READ OWNER_EXECUTE)
    execute_process(COMMAND ${RTRT} play ${WORK_DIR}/nowhere.json --headless --frames 1
        -o ${WORK_DIR}/read_only/f_%02d${EXT} RESULT_VARIABLE status ERROR_VARIABLE stderr)
    file(CHMOD ${WORK_DIR}/read_only DIRECTORY_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
    if(NOT status EQUAL 2 OR NOT stderr MATCHES "cannot write into the folder .*read_only: Permission denied")
        message(FATAL_ERROR "unwritable folder: status ${status}: ${stderr}")
    endif()
endif()

# JSON that is not JSON, or repeats a key, is named in rtrt's words with its line and column.
file(WRITE ${WORK_DIR}/duplicate_key.json "{\n  \"instances\": [],\n  \"instances\": []\n}\n")
expect_failure(duplicate_key 2 "duplicate_key.json: line 3, column 3: malformed JSON: the key \"instances\" is given twice in one object" render ${WORK_DIR}/duplicate_key.json)
file(WRITE ${WORK_DIR}/nan.json "{ \"instances\": [], \"camera\": { \"position\": [0, NaN, 1] } }")
expect_failure(nan_literal 2 "nan.json: line 1, column 48: malformed JSON: NaN is not a JSON number" render ${WORK_DIR}/nan.json)
file(WRITE ${WORK_DIR}/overflow.json "{ \"instances\": [],\n\"camera\": { \"position\": [0, 1e999, 1] } }")
expect_failure(overflow 2 "overflow.json: line 2, column 29: malformed JSON: the number 1e999 is beyond the range of a double" render ${WORK_DIR}/overflow.json)

# A benchmark's report is checked when the command line is read, before the run: a missing
# folder, a folder, or a device (which the rename would replace) is refused with status 2, one line.
file(MAKE_DIRECTORY ${WORK_DIR}/reports)
foreach(report "${WORK_DIR}/reports/no/such/r.json" "${WORK_DIR}/reports" "/dev/null")
    execute_process(COMMAND ${RTRT} bench frame ${SOURCE_DIR}/assets/scenes/demo_glass.json
        --backend cpu --frames 1 --warmup 0 --size 8x8 -o ${report}
        RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
    if(NOT status EQUAL 2 OR NOT stderr MATCHES "^rtrt: error: --output: " OR stdout MATCHES "medians")
        message(FATAL_ERROR "bench -o ${report}: status ${status}, expected 2 before the run\n${stdout}${stderr}")
    endif()
endforeach()
if(NOT EXISTS /dev/null OR IS_DIRECTORY /dev/null)
    message(FATAL_ERROR "/dev/null was replaced")
endif()
message(STATUS "bench reports: ok")

# Every scene of a benchmark is read before the first is played: a bad second scene ends the run
# with status 2 before anything is measured.
foreach(bench frame runtime)
    if(bench STREQUAL frame)
        set(extra --backend cpu --warmup 0 --size 8x8)
    else()
        set(extra)
    endif()
    execute_process(COMMAND ${RTRT} bench ${bench} ${SOURCE_DIR}/assets/scenes/demo_glass.json
        ${WORK_DIR}/malformed.json --frames 1 ${extra}
        RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
    if(NOT status EQUAL 2 OR NOT stderr MATCHES "malformed.json: line 1" OR stdout MATCHES "medians")
        message(FATAL_ERROR "bench ${bench} with a bad second scene: status ${status}, expected 2 before the run\n${stdout}${stderr}")
    endif()
endforeach()
message(STATUS "bench scenes read first: ok")
execute_process(COMMAND ${RTRT} bench frame ${SOURCE_DIR}/assets/scenes/demo_glass.json
    --backend cpu --trace-bands 2 --frames 1
    RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT status EQUAL 2 OR NOT stderr MATCHES "--trace-bands: 2: .*CUDA back end" OR stdout MATCHES "medians")
    message(FATAL_ERROR "bench frame --trace-bands with the CPU back end: status ${status}\n${stdout}${stderr}")
endif()


# A paper-scene benchmark none of whose models is there measures nothing: refused before any work
# (it exited 0 with an empty report), saying what to fetch. The model folder is restored after.
set(saved_model_dir "$ENV{RTRT_MODEL_DIR}")
file(MAKE_DIRECTORY ${WORK_DIR}/no_models)
set(ENV{RTRT_MODEL_DIR} ${WORK_DIR}/no_models)
expect_failure(bench_cpu_no_models 2
    "--models: none of the models asked for is there (dragon, teapot); run rtrt fetch-models"
    bench cpu --models dragon,teapot --frames 1)
expect_failure(bench_convert_no_models 2 "none of the models asked for is there (dragon_res4)"
    bench convert --models dragon_res4)
# A bad model late in the list fails the benchmark before any model is measured (the cube's rows
# were measured, printed and then thrown away with the report).
file(MAKE_DIRECTORY ${WORK_DIR}/bad_models)
file(WRITE ${WORK_DIR}/bad_models/dragon_vrip_res3.ply.gz "not a gzip stream\n")
set(ENV{RTRT_MODEL_DIR} ${WORK_DIR}/bad_models)
execute_process(COMMAND ${RTRT} bench cpu --models cube,dragon_res3 --builders binned --frames 1
    RESULT_VARIABLE status OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT status EQUAL 2 OR NOT stderr MATCHES "dragon_vrip_res3.ply.gz" OR stdout MATCHES "\ncube ")
    message(FATAL_ERROR "bench cpu with a bad model after the cube: status ${status}\n${stdout}${stderr}")
endif()
set(ENV{RTRT_MODEL_DIR} "${saved_model_dir}")

# info takes what render and play take, a scene's bare name, and says what is wrong with a folder
# (it said "unknown mesh file extension").
expect_one_line_failure(info_folder "${WORK_DIR}: is a folder; name a file in it" info ${WORK_DIR})
execute_process(COMMAND ${RTRT} info demo_glass RESULT_VARIABLE status OUTPUT_VARIABLE stdout
    ERROR_VARIABLE stderr)
if(NOT status EQUAL 0 OR NOT stdout MATCHES "demo_glass.json: scene file")
    message(FATAL_ERROR "info demo_glass: status ${status}: ${stdout}${stderr}")
endif()

# The window's --frames and script are checked before a window opens, each with its own reason
# (every one had been "the window takes a frame count N"; a screenshot after the last frame was
# dropped silently).
expect_one_line_failure(window_frames_zero "--frames: 0: N is how many frames: at least 1"
    play default --frames 0)
expect_one_line_failure(window_frames_many "--frames: 20000000: frames end at 10,000,000"
    play default --frames 20000000)
expect_one_line_failure(window_frames_range
    "--frames: 2:4: the window takes a frame count N (A:B ranges are for --headless)"
    play default --frames 2:4)
file(WRITE ${WORK_DIR}/late.script "20 screenshot ${WORK_DIR}/late${EXT}\n")
expect_one_line_failure(window_late_event
    "${WORK_DIR}/late.script: has an event at frame 20, but --frames 10 closes the window after frame 9"
    play default --script ${WORK_DIR}/late.script --frames 10)
# A scripted screenshot over a file the scene read is refused before the window opens (it had
# failed when its frame came, after frames were recorded).
file(WRITE ${WORK_DIR}/shot_scene.json "{ \"instances\": [] }")
file(WRITE ${WORK_DIR}/over_scene.script "1 screenshot ${WORK_DIR}/shot_scene.json\n")
expect_one_line_failure(window_shot_over_scene
    "${WORK_DIR}/over_scene.script: line 1: screenshot \"${WORK_DIR}/shot_scene.json\" would be written over a file of the scene"
    play ${WORK_DIR}/shot_scene.json --script ${WORK_DIR}/over_scene.script)
