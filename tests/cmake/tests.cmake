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

# The verify report's verdict (samples/osd-cull/verify_report.*), judged on made-up totals.
if(TARGET test_cli_verify)
  target_sources(test_cli_verify PRIVATE ${PROJECT_SOURCE_DIR}/samples/osd-cull/verify_report.cpp)
  target_include_directories(test_cli_verify PRIVATE ${PROJECT_SOURCE_DIR}/samples/osd-cull)
endif()

# Without the data folder the shape suites run one test each that skips naming the folder.
foreach(_suite test_patch_accuracy:Shapes/ShapeAccuracy test_shapes_load:SharedData/ShapeIndex)
  string(REPLACE ":" ";" _parts ${_suite})
  list(GET _parts 0 _exe)
  list(GET _parts 1 _name)
  string(REPLACE "/" "." _test ${_name})
  if(TARGET ${_exe})
    add_test(NAME DataSkips.${_test}SkipsNamingTheMissingFolder
      COMMAND ${_exe} --gtest_filter=${_name}.*)
    set_tests_properties(DataSkips.${_test}SkipsNamingTheMissingFolder PROPERTIES
      ENVIRONMENT OSD_CULL_DATA_DIR=/nonexistent/osd_cull_data
      PASS_REGULAR_EXPRESSION [=[/NoData.*shared data folder not found at "/nonexistent/osd_cull_data".*SKIPPED \] .*/NoData]=])
  endif()
endforeach()

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

# Issue 22: every plot script of docs/results answers --help, draws its picture from the
# committed inputs and refuses an empty input with a one-line error (scripts/plots/check_plots.py).
if(OSD_CULL_PYTHON3)
  foreach(_plot accuracy_vs_time animation_speed backpatch_kernel_cost backpatch_tess
          displacement_table1 frame_cost frame_cost_tables large_coordinates occlusion_rotation
          plan scale)
    add_test(NAME Plots.${_plot} COMMAND ${OSD_CULL_PYTHON3}
      ${PROJECT_SOURCE_DIR}/scripts/plots/check_plots.py --root ${PROJECT_SOURCE_DIR} --only ${_plot})
    set_tests_properties(Plots.${_plot} PROPERTIES PASS_REGULAR_EXPRESSION "plot ${_plot}: ok"
      FAIL_REGULAR_EXPRESSION "FAILED")
  endforeach()
endif()

# Issue 22: every benchmark runs end to end at its smallest size (label bench-smoke): it exits 0
# and prints at least one row of figures (a Markdown table row, or its own table's row or
# summary line where it prints no Markdown). The figures themselves are not checked
# here (benchmarks, not timed tests); a benchmark that no longer starts, or prints no table,
# fails. Meshes from ../shared/data where the default is a shipped mesh.
set(_shapes ${PROJECT_SOURCE_DIR}/../shared/data/shapes)
function(osd_cull_bench_smoke name)
  if(NOT TARGET ${name})
    return()
  endif()
  if(NOT DEFINED OSD_CULL_SMOKE_ROW)
    set(OSD_CULL_SMOKE_ROW "\n\\|[^\n]*\\| [0-9][0-9.]*%? \\|")  # a table row with a figure
  endif()
  add_test(NAME BenchSmoke.${name} COMMAND ${name} ${ARGN})
  set_tests_properties(BenchSmoke.${name} PROPERTIES LABELS bench-smoke TIMEOUT 600
    PASS_REGULAR_EXPRESSION "${OSD_CULL_SMOKE_ROW}" FAIL_REGULAR_EXPRESSION "rror:|Validation")
endfunction()
if(EXISTS ${_shapes}/catmark_cube.obj)
  osd_cull_bench_smoke(bench-cull --width 64 --height 64 --repeats 1 --mesh ${_shapes}/catmark_cube.obj
    --levels 1 --tess 1 --views 1 --methods frustum,tcone --frame-modes all --kernel-tess 1
    --break-even-tess 1 --break-even-views 1 --floor-grids 10 --floor-views 1 --parts 14)
  osd_cull_bench_smoke(bench-displaced --mesh ${_shapes}/catmark_cube.obj --levels 1 --views 1 --repeats 1)
  osd_cull_bench_smoke(bench-displaced-tess --mesh ${_shapes}/catmark_cube.obj --level 1 --views 1
    --repeats 1 --size 64 --pixels 8)
  osd_cull_bench_smoke(bench-draw --width 64 --height 64 --repeats 1 --mesh ${_shapes}/catmark_cube.obj
    --max-one-draw-level 2 --nu 4 --nv 4)
  osd_cull_bench_smoke(bench-extraction --mesh ${_shapes}/catmark_cube.obj --levels 1 --repeats 1)
  osd_cull_bench_smoke(bench-update ${_shapes}/catmark_cube.obj --frames 2 --levels 1)
endif()
osd_cull_bench_smoke(bench-animation --only 1 --size 64 --frames 2)
osd_cull_bench_smoke(bench-frame-cost --width 64 --height 64 --repeats 1 --frames 2 --bigguy-level 0
  --tess 1 --paths default-orbit --only F)
set(OSD_CULL_SMOKE_ROW "\n +2 +192 +1 +2 +[0-9.]+ +[0-9.]+ +[0-9.]+")
osd_cull_bench_smoke(bench-instances --counts 1,2 --frames 2 --tess 1)
set(OSD_CULL_SMOKE_ROW "frames failing [^\n]*: 0 of 3")
osd_cull_bench_smoke(bench-scene-image --frames 3 --width 32 --height 32 --tess 1 --every 1)
unset(OSD_CULL_SMOKE_ROW)
osd_cull_bench_smoke(bench-occlusion --width 64 --height 64 --repeats 1 --views 2 --sequence 2
  --scenes default --only 1)
osd_cull_bench_smoke(bench-plan --cases builtin --tess 1 --frames 1 --warmup 1 --width 64 --height 64)
osd_cull_bench_smoke(bench-scale --grids 10,20 --views 1 --tess 1 --width 32 --height 32 --repeats 1)
