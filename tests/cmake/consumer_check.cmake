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
file(GLOB_RECURSE headers ${prefix}/include/osd_cull/*.h)
foreach(h IN LISTS headers)
  file(STRINGS ${h} bad REGEX "^#include [<\"](shared|adapters)/")
  if(bad)
    message(FATAL_ERROR "${h}: '${bad}' does not resolve when installed; write osd_cull/...")
  endif()
endforeach()
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
run(${WORK_DIR}/build/consumer)
