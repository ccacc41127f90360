# cmake -DBUILD_DIR=... -DWORK_DIR=... -DCONSUMER_SOURCE=... -DGENERATOR=...
#       [-DCXX_FLAGS=...] [-DLINKER_FLAGS=...] -P consumer_check.cmake
# Installs the build into a temporary prefix, checks the header layout, then configures,
# builds and runs the consumer with the build's compiler flags (a sanitizer build's
# consumer must be built with the sanitizer too, or it does not link).
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message("${out}")
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# Only include/osd_cull/ on the consumer's include path, and installed headers that name
# each other the way a consumer can resolve (<osd_cull/...>, never "shared/..." or
# "adapters/...", which only the source tree resolves).
file(GLOB top RELATIVE ${prefix}/include ${prefix}/include/*)
if(NOT top STREQUAL "osd_cull")
  message(FATAL_ERROR "include/ holds '${top}'; expected only osd_cull/")
endif()
# Fails when a line of one of the files after `why` matches `regex`.
function(forbid_lines regex why)
  foreach(f IN LISTS ARGN)
    file(STRINGS ${f} bad REGEX "${regex}")
    if(bad)
      message(FATAL_ERROR "${f}: '${bad}' ${why}")
    endif()
  endforeach()
endfunction()
file(GLOB_RECURSE headers ${prefix}/include/osd_cull/*.h)
forbid_lines("^#include [<\"](shared|adapters)/"
  "does not resolve when installed; write osd_cull/..." ${headers})
foreach(required osd_cull/version.h osd_cull/shared/cull_layout.h
                 osd_cull/adapters/load_mesh.h osd_cull/patch/extract_patches.h)
  if(NOT EXISTS ${prefix}/include/${required})
    message(FATAL_ERROR "include/${required} was not installed")
  endif()
endforeach()

run(${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${WORK_DIR}/build -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release
    "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${LINKER_FLAGS}")
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)

# Shaders are embedded as SPIR-V: neither the package nor the consumer names or links glslang.
file(GLOB_RECURSE package_files ${prefix}/lib*/cmake/osd_cull/*.cmake)
forbid_lines("^[^#]*glslang" "names glslang" ${package_files})
find_program(NM nm REQUIRED)
execute_process(COMMAND ${NM} -C ${WORK_DIR}/build/consumer OUTPUT_VARIABLE symbols
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "nm ${WORK_DIR}/build/consumer failed")
endif()
string(REGEX MATCH "[^\n]*glslang::[^\n]*" glslang_symbol "${symbols}")
if(glslang_symbol)
  message(FATAL_ERROR "the consumer contains glslang code: ${glslang_symbol}")
endif()
run(${WORK_DIR}/build/consumer)
