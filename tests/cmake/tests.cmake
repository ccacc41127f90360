# Install-and-consume check: installs this build into a temporary prefix, then configures,
# builds and runs a tiny project that does find_package(osd_cull) and links
# osd_cull::osd_cull and osd_cull::adapters, with this build's compiler flags (sanitizers),
# without glslang, and runs a cull with the embedded SPIR-V.
add_test(NAME InstalledPackage.ConsumerBuildsAndRuns
  COMMAND ${CMAKE_COMMAND}
    -DBUILD_DIR=${PROJECT_BINARY_DIR}
    -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/consumer-check
    -DCONSUMER_SOURCE=${CMAKE_CURRENT_SOURCE_DIR}/cmake/consumer
    -DGENERATOR=${CMAKE_GENERATOR}
    "-DCXX_FLAGS=${CMAKE_CXX_FLAGS}"
    "-DLINKER_FLAGS=${CMAKE_EXE_LINKER_FLAGS}"
    -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/consumer_check.cmake)
set_tests_properties(InstalledPackage.ConsumerBuildsAndRuns PROPERTIES
  TIMEOUT 600 PASS_REGULAR_EXPRESSION
  "consumer: osd_cull ${PROJECT_VERSION} \\(headers ${PROJECT_VERSION}\\)\nconsumer: cube patches=96 shift=10.000000\n(osd_cull: Vulkan device[^\n]*\n)?consumer: cull survivors framed=96 away=0")

# The minimal integration example runs and draws every patch of the built-in mesh.
if(TARGET osd-cull-minimal)
  file(MAKE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/minimal-check)
  add_test(NAME Samples.MinimalDrawsEveryPatchOfTheBuiltInMesh COMMAND osd-cull-minimal
    WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/minimal-check)
  set_tests_properties(Samples.MinimalDrawsEveryPatchOfTheBuiltInMesh PROPERTIES
    PASS_REGULAR_EXPRESSION "504 Bezier \\+ 24 Gregory patches[^\n]*\n(osd_cull: Vulkan device[^\n]*\n)?drew 528 patches")
endif()

# The integration sample: its own device, render passes and Osd::Mesh, osd_cull culling its
# draws; it exits 0 only when its image equals osd_cull's renderer's and validation is quiet.
if(TARGET osd-cull-integration)
  add_test(NAME Samples.IntegrationImageEqualsOsdCullsRenderer
    COMMAND osd-cull-integration --frames 3 --size 160x120 --validate)
  set_tests_properties(Samples.IntegrationImageEqualsOsdCullsRenderer PROPERTIES
    PASS_REGULAR_EXPRESSION "integration: PASS" TIMEOUT 300)
endif()

# The viewer's key and script logic (samples/viewer/view_state.*) and, under Xvfb, the
# `osd-cull view` window itself.
if(TARGET osd_cull_viewer AND TARGET test_viewer)
  target_link_libraries(test_viewer PRIVATE osd_cull_viewer)
  target_compile_definitions(test_viewer PRIVATE OSD_CULL_HAVE_VIEWER=1)
endif()

# The layer order of DESIGN.md: no include runs upward (scripts/check_layers.py), the check
# fails on a planted upward include, and docs/architecture.md's layer picture is current.
find_program(OSD_CULL_PYTHON3 python3)
if(OSD_CULL_PYTHON3)
  set(_layers ${OSD_CULL_PYTHON3} ${PROJECT_SOURCE_DIR}/scripts/check_layers.py --root ${PROJECT_SOURCE_DIR})
  add_test(NAME Layers.NoIncludeRunsUpward COMMAND ${_layers})
  set_tests_properties(Layers.NoIncludeRunsUpward PROPERTIES
    PASS_REGULAR_EXPRESSION "includes, 0 upward")
  add_test(NAME Layers.CheckFailsOnAPlantedUpwardInclude
    COMMAND ${_layers} --plant osd_cull/patch/patch_set.h:osd_cull/frame/cull_frame.h
                       --plant osd_cull/scene/procedural.h:osd_cull/plan/planner.h)
  set_tests_properties(Layers.CheckFailsOnAPlantedUpwardInclude PROPERTIES
    PASS_REGULAR_EXPRESSION "layer 'patch' may not use layer 'frame'.*layer 'scene' may not use layer 'plan'.*2 upward")
  add_test(NAME Layers.DocIsCurrent COMMAND ${_layers} --check-doc)
  set_tests_properties(Layers.DocIsCurrent PROPERTIES PASS_REGULAR_EXPRESSION "picture is current")
endif()

# Issue 22: no function over 120 lines without a written reason (scripts/check_function_length.py),
# the check fails on a planted long function, lets one with a reason marker through, and its
# brace scanner reads its known cases.
function(osd_cull_function_length_test name pass_regex)
  add_test(NAME FunctionLength.${name} COMMAND ${OSD_CULL_PYTHON3}
    ${PROJECT_SOURCE_DIR}/scripts/check_function_length.py --root ${PROJECT_SOURCE_DIR} ${ARGN})
  set_tests_properties(FunctionLength.${name} PROPERTIES PASS_REGULAR_EXPRESSION "${pass_regex}")
endfunction()
if(OSD_CULL_PYTHON3)
  osd_cull_function_length_test(NoLongFunctionWithoutAReason
    "functions, [0-9]+ long with a reason, [0-9]+ on the allow-list, 0 failing")
  osd_cull_function_length_test(CheckFailsOnAPlantedLongFunction
    "osd_cull/measure/calibrate.cpp: plantedLongFunction is 125 lines.*samples/osd-cull/main.cpp: plantedLongFunction is 125 lines.*, 2 failing"
    --plant osd_cull/measure/calibrate.cpp --plant samples/osd-cull/main.cpp)
  osd_cull_function_length_test(AReasonMarkerExcusesALongFunction "[1-9][0-9]* long with a reason"
    --plant osd_cull/measure/calibrate.cpp:r)
  set_tests_properties(FunctionLength.AReasonMarkerExcusesALongFunction PROPERTIES
    FAIL_REGULAR_EXPRESSION "plantedLongFunction")
  osd_cull_function_length_test(ScannerReadsItsKnownCases "self-test: all [0-9]+ cases pass" --self-test)
endif()
