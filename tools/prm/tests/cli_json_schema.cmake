# Every prm command's --json report follows one schema (docs/cli-json.md): runs each command on small inputs and
# checks "schema", "command" and the shared keys it must carry. Also: render draws a .prm (non-blank PNG), decode
# writes a float PLY by default and a double PLY with --double, and every command exits 4 on a missing input file,
# with the JSON error object on stderr.
#   cmake -DPRM=<prm> -DPNG_CHECK=<prm_png_not_blank> -DDATA=<common/tests/data> -DWORK=<scratch dir>
#         [-DDRACO_ENCODER=<draco_encoder or empty>] -P cli_json_schema.cmake
file(MAKE_DIRECTORY "${WORK}")
set(schema_version 1)  # json_report.h kJsonSchemaVersion

# run_json(<command> <shared keys...> ARGS <arguments...>): runs `prm <arguments> --json`, parses stdout.
function(run_json command)
  cmake_parse_arguments(R "" "" "KEYS;ARGS" ${ARGN})
  execute_process(COMMAND "${PRM}" ${R_ARGS} --json RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "prm ${R_ARGS} --json: exit ${rc}\n${out}${err}")
  endif()
  string(JSON schema ERROR_VARIABLE jerr GET "${out}" schema)
  if(jerr OR NOT schema EQUAL schema_version)
    message(FATAL_ERROR "prm ${R_ARGS} --json: \"schema\" is '${schema}', expected ${schema_version} (${jerr}):\n${out}")
  endif()
  string(JSON got GET "${out}" command)
  if(NOT got STREQUAL command)
    message(FATAL_ERROR "prm ${R_ARGS} --json: \"command\" is '${got}', expected '${command}'")
  endif()
  foreach(key IN LISTS R_KEYS)
    string(REPLACE "." ";" path "${key}")
    string(JSON value ERROR_VARIABLE jerr GET "${out}" ${path})
    if(jerr)
      message(FATAL_ERROR "prm ${R_ARGS} --json: no \"${key}\" in the report:\n${out}")
    endif()
  endforeach()
  set(last_json "${out}" PARENT_SCOPE)
  message(STATUS "prm ${command} --json: schema ${schema}, keys ${R_KEYS}")
endfunction()

set(mesh "${DATA}/tet.off")
set(counts vertices triangles)
run_json(encode KEYS input output ${counts} bytes.total bits_per_vertex.total bytes.positions seconds
         ARGS encode "${mesh}" -o "${WORK}/tet.prm")
run_json(decode KEYS input output ${counts} bytes.total bits_per_vertex.total seconds
         ARGS decode "${WORK}/tet.prm" -o "${WORK}/tet_float.ply")
run_json(unpack KEYS input output ${counts} bytes.total bits_per_vertex.total bytes.connectivity seconds
         ARGS unpack "${WORK}/tet.prm" -o "${WORK}/tet_unpacked.ply")
run_json(info KEYS input ${counts} bytes.total bits_per_vertex.total boundary_loops ARGS info "${WORK}/tet.prm")
run_json(info KEYS input ${counts} ARGS info "${mesh}")
run_json(compare KEYS distance.rms_rel distance.max_rel distance.rms distance.max seconds
         ARGS compare "${mesh}" "${WORK}/tet_float.ply" --samples 1000)
run_json(repair KEYS input output ${counts} seconds ARGS repair "${DATA}/open_box.off" -o "${WORK}/box.ply")
run_json(reliefs KEYS input output ${counts} seconds ARGS reliefs "${DATA}/cube_quads.obj" -o "${WORK}/cube_reliefs.ply")
run_json(remesh KEYS input output ${counts} distance.rms_rel distance.max_rel seconds
         ARGS remesh "${DATA}/cube_quads.obj" -o "${WORK}/cube_prm.ply" --grid-fraction 0.1)
run_json(pack KEYS input output ${counts} bytes.total bits_per_vertex.total bytes.connectivity distance.rms_rel
         distance.max_rel seconds n_o n_r boundary_loops_in boundary_loops_out holes_closed boundary_vertices_removed relief_costs.prologue_bits relief_costs.unattributed_bits
         relief_costs.reliefs.0.bits relief_costs.reliefs.0.msq_quarters
         ARGS pack "${DATA}/cube_quads.obj" -o "${WORK}/cube.prm" --grid-fraction 0.1 --relief-costs)
# --mode (issue 22): auto keeps the smaller stream and says why; the 8-vertex cube is coded as it is.
run_json(pack KEYS mode mode_requested mode_reason candidates.prm.bytes candidates.general.bytes
         candidates.general.bits n_r_over_n_o distance.rms_rel
         ARGS pack "${DATA}/cube_quads.obj" -o "${WORK}/cube_auto.prm" --target-error 1e-3)
string(JSON mode GET "${last_json}" mode)
string(JSON n_r GET "${last_json}" n_r)
if(NOT mode STREQUAL "general" OR NOT n_r EQUAL 8)
  message(FATAL_ERROR "prm pack cube_quads.obj --target-error 1e-3: mode ${mode} with ${n_r} vertices, expected "
                      "general with 8:\n${last_json}")
endif()
run_json(pack KEYS mode candidates.prm.made candidates.general.bits
         ARGS pack "${DATA}/cube_quads.obj" -o "${WORK}/cube_general.prm" --target-error 1e-3 --mode general)
string(JSON made GET "${last_json}" candidates prm made)
if(made)
  message(FATAL_ERROR "prm pack --mode general made a piecewise regular candidate:\n${last_json}")
endif()
# check_local_refinement(<command> <ON|OFF> <arguments...>): `prm <command> <arguments> --json` says local_refinement
# <ON|OFF> (JSON true: ON), and refined no vertex when off.
function(check_local_refinement command expected)
  run_json(${command} KEYS local_refinement refined_vertices ARGS ${command} ${ARGN})
  string(JSON refined GET "${last_json}" local_refinement)
  string(JSON inserted GET "${last_json}" refined_vertices)
  if(NOT refined STREQUAL expected OR (NOT refined AND NOT inserted EQUAL 0))
    message(FATAL_ERROR "prm ${command} ${ARGN}: local_refinement ${refined} (expected ${expected}), ${inserted} "
                        "vertices inserted:\n${last_json}")
  endif()
endfunction()
# The local refinement (issue 22): the default with a target error at every --effort but 0; --no-local-refinement
# turns it off, --local-refinement asks for it at effort 0; the two together are a usage error (exit 1).
foreach(spec "ON|" "OFF|--no-local-refinement" "OFF|--effort;0" "ON|--effort;0;--local-refinement")  # JSON true: ON
  string(REPLACE "|" ";" spec "${spec}")
  list(POP_FRONT spec expected)
  check_local_refinement(pack ${expected} "${DATA}/cube_quads.obj" -o "${WORK}/cube_refined.prm" --target-error 1e-3
                         --mode prm ${spec})
endforeach()
execute_process(COMMAND "${PRM}" pack "${DATA}/cube_quads.obj" -o "${WORK}/cube_refined.prm" --target-error 1e-3
                        --local-refinement --no-local-refinement RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "prm pack --local-refinement --no-local-refinement: exit ${rc}, expected 1 (usage)")
endif()
# --target-bytes (issue 23): the stream fits the budget and the report names the search; a budget below every stream
# is exit 3 with the error object (the general path alone, so that this is a few milliseconds).
run_json(pack KEYS target_bytes target_error bytes_search bytes_search_finest bytes.total distance.rms_rel
         ARGS pack "${DATA}/cube_quads.obj" -o "${WORK}/cube_bytes.prm" --target-bytes 200 --mode general)
string(JSON total GET "${last_json}" bytes total)
file(SIZE "${WORK}/cube_bytes.prm" written)
if(total GREATER 200 OR NOT written EQUAL total)
  message(FATAL_ERROR "prm pack --target-bytes 200: ${total} bytes reported, ${written} written:\n${last_json}")
endif()
execute_process(COMMAND "${PRM}" pack "${DATA}/cube_quads.obj" -o "${WORK}/cube_bytes_small.prm" --target-bytes 50
                        --mode general --json RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCH "[^\n]+\n?$" last_line "${err}")
string(JSON code ERROR_VARIABLE jerr GET "${last_line}" error code)
if(NOT rc EQUAL 3 OR jerr OR NOT code EQUAL 3 OR NOT err MATCHES "no stream fits 50 bytes")
  message(FATAL_ERROR "prm pack --target-bytes 50 (below every stream): exit ${rc}, expected 3 with the error object:\n${err}")
endif()
# remesh keeps an open input's boundary loops (issue 22), and closes them with --fill-holes.
run_json(remesh KEYS boundary_loops_in boundary_loops_out holes_closed
         ARGS remesh "${DATA}/open_box.off" -o "${WORK}/open_box_prm.ply" --grid-fraction 0.1)
string(JSON loops_in GET "${last_json}" boundary_loops_in)
string(JSON loops_out GET "${last_json}" boundary_loops_out)
string(JSON closed GET "${last_json}" holes_closed)
if(NOT loops_in EQUAL 1 OR NOT loops_out EQUAL 1 OR NOT closed EQUAL 0)
  message(FATAL_ERROR "prm remesh open_box.off: loops ${loops_in} in, ${loops_out} out, ${closed} closed; expected "
                      "1, 1, 0:\n${last_json}")
endif()
run_json(remesh KEYS boundary_loops_in boundary_loops_out holes_closed
         ARGS remesh "${DATA}/open_box.off" -o "${WORK}/open_box_filled_prm.ply" --grid-fraction 0.1 --fill-holes)
string(JSON loops_out GET "${last_json}" boundary_loops_out)
string(JSON closed GET "${last_json}" holes_closed)
if(NOT loops_out EQUAL 0 OR NOT closed EQUAL 1)
  message(FATAL_ERROR "prm remesh open_box.off --fill-holes: loops ${loops_out} out, ${closed} closed; expected "
                      "0, 1:\n${last_json}")
endif()
# remesh --target-error refines locally as pack does (issue 22), unless --no-local-refinement; a grid given: never.
foreach(spec "ON|--target-error;1e-3" "OFF|--target-error;1e-3;--no-local-refinement" "OFF|--grid-fraction;0.1")
  string(REPLACE "|" ";" spec "${spec}")
  list(POP_FRONT spec expected)
  check_local_refinement(remesh ${expected} "${DATA}/cube_quads.obj" -o "${WORK}/cube_refined_prm.ply" ${spec})
endforeach()
run_json(render KEYS input output ${counts} seconds ARGS render "${WORK}/tet.prm" -o "${WORK}/tet.png" --size 64x64)

# render of a .prm draws the mesh: more than the background in the picture.
execute_process(COMMAND "${PNG_CHECK}" "${WORK}/tet.png" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "prm render of a .prm: blank or unreadable picture: ${out}${err}")
endif()

# ... and of a glTF asset whose primitive is a PRM stream (PRM_mesh_compression); compare reads both as well.
execute_process(COMMAND "${PRM}" pack "${DATA}/cube_quads.obj" -o "${WORK}/cube.glb" --grid-fraction 0.1
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "prm pack to .glb: exit ${rc}: ${err}")
endif()
run_json(render KEYS triangles ARGS render "${WORK}/cube.glb" -o "${WORK}/cube.png" --size 64x64)
execute_process(COMMAND "${PNG_CHECK}" "${WORK}/cube.png" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "prm render of a PRM-compressed .glb: blank or unreadable picture: ${out}${err}")
endif()
run_json(compare KEYS distance.max ARGS compare "${WORK}/tet.prm" "${WORK}/tet_float.ply" --samples 1000)
string(JSON hausdorff GET "${last_json}" distance max)
if(NOT hausdorff LESS 1e-6)  # the stream and its float decoding: the same surface up to float rounding
  message(FATAL_ERROR "prm compare of a .prm and its decoding: Hausdorff ${hausdorff}")
endif()

# decode and unpack write float PLY positions by default, double with --double.
function(expect_ply_type ply type)
  file(READ "${ply}" header LIMIT 400)
  if(NOT header MATCHES "property ${type} x\nproperty ${type} y\nproperty ${type} z\n")
    message(FATAL_ERROR "${ply}: positions are not '${type}':\n${header}")
  endif()
endfunction()
expect_ply_type("${WORK}/tet_float.ply" float)
expect_ply_type("${WORK}/tet_unpacked.ply" float)
foreach(command decode unpack)
  execute_process(COMMAND "${PRM}" ${command} "${WORK}/tet.prm" -o "${WORK}/tet_${command}_double.ply" --double
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "prm ${command} --double: exit ${rc}")
  endif()
  expect_ply_type("${WORK}/tet_${command}_double.ply" double)
endforeach()

# Draco's encoder reads the default PLY (it refuses double positions).
if(DRACO_ENCODER)
  execute_process(COMMAND "${DRACO_ENCODER}" -i "${WORK}/tet_float.ply" -o "${WORK}/tet.drc"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "draco_encoder refuses prm decode's PLY: ${out}${err}")
  endif()
  message(STATUS "draco_encoder reads prm decode's PLY")
else()
  message(STATUS "draco_encoder not found (Debian package draco): its check of the decoded PLY is skipped")
endif()

# A missing input file is exit 4 in every command, and with --json the error object is the last line on stderr.
set(missing "${WORK}/does_not_exist")
foreach(args "info|${missing}.ply" "compare|${missing}.ply|${mesh}" "compare|${mesh}|${missing}.ply"
             "repair|${missing}.ply|-o|${WORK}/m.ply" "reliefs|${missing}.ply|-o|${WORK}/m.ply"
             "render|${missing}.ply|-o|${WORK}/m.png" "render|${missing}.prm|-o|${WORK}/m.png"
             "remesh|${missing}.ply|-o|${WORK}/m.ply|--grid-fraction|0.1" "encode|${missing}.ply|-o|${WORK}/m.prm"
             "decode|${missing}.prm|-o|${WORK}/m.ply" "unpack|${missing}.prm|-o|${WORK}/m.ply"
             "unpack|${missing}.glb|-o|${WORK}/m.glb" "info|${missing}.prm" "info|${missing}.glb"
             "pack|${missing}.ply|-o|${WORK}/m.prm|--grid-fraction|0.1")
  string(REPLACE "|" ";" a "${args}")
  execute_process(COMMAND "${PRM}" ${a} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 4)
    message(FATAL_ERROR "prm ${a} (missing input): exit ${rc}, expected 4\n${err}")
  endif()
  execute_process(COMMAND "${PRM}" ${a} --json RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(STRIP "${err}" err)
  string(REGEX REPLACE "^.*\n" "" last "${err}")
  string(JSON code ERROR_VARIABLE jerr GET "${last}" error code)
  string(JSON schema ERROR_VARIABLE jerr2 GET "${last}" schema)
  if(NOT rc EQUAL 4 OR jerr OR jerr2 OR NOT code EQUAL 4 OR NOT schema EQUAL schema_version)
    message(FATAL_ERROR "prm ${a} --json (missing input): exit ${rc}, stderr's last line is not the error object "
                        "with code 4 and schema ${schema_version}:\n${err}")
  endif()
endforeach()
message(STATUS "missing input: exit 4 and the JSON error in every command")

# A bad command line with --json: exit 1 and the error object too.
execute_process(COMMAND "${PRM}" info --json --weld-tolerance -1 "${mesh}" RESULT_VARIABLE rc ERROR_VARIABLE err)
string(STRIP "${err}" err)
string(REGEX REPLACE "^.*\n" "" last "${err}")
string(JSON name ERROR_VARIABLE jerr GET "${last}" error name)
if(NOT rc EQUAL 1 OR jerr OR NOT name STREQUAL "usage")
  message(FATAL_ERROR "prm info --json with a bad option: exit ${rc}, error object '${last}'")
endif()
