# Finds every third-party dependency and gives each an imported target.
# Also used by the installed package config (osd_cull-config.cmake), so consumers
# resolve the same targets.
include_guard(GLOBAL)
include(CMakeFindDependencyMacro)

find_package(Threads REQUIRED)
find_package(Vulkan REQUIRED)
# glslang is found by osd_cull/CMakeLists.txt: only the build links it (shaders are compiled
# to SPIR-V at build time), not the library's consumers.
find_package(glm CONFIG REQUIRED)
find_package(PNG REQUIRED)
# OpenEXR: float displacement maps (adapters/image_exr.cpp).
find_package(OpenEXR CONFIG REQUIRED)

# OpenSubdiv: Debian's exported config names static libraries that are not shipped,
# so build our own imported target from the header and the shared library.
if(NOT TARGET OpenSubdiv::osdCPU)
  find_path(OSD_CULL_OPENSUBDIV_INCLUDE_DIR opensubdiv/far/topologyRefiner.h REQUIRED)
  find_library(OSD_CULL_OPENSUBDIV_CPU_LIBRARY osdCPU REQUIRED)
  add_library(OpenSubdiv::osdCPU UNKNOWN IMPORTED)
  set_target_properties(OpenSubdiv::osdCPU PROPERTIES
    IMPORTED_LOCATION "${OSD_CULL_OPENSUBDIV_CPU_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OSD_CULL_OPENSUBDIV_INCLUDE_DIR}")
endif()
if(NOT TARGET OpenSubdiv::osdGPU)
  find_library(OSD_CULL_OPENSUBDIV_GPU_LIBRARY osdGPU)
  if(OSD_CULL_OPENSUBDIV_GPU_LIBRARY)
    add_library(OpenSubdiv::osdGPU UNKNOWN IMPORTED)
    set_target_properties(OpenSubdiv::osdGPU PROPERTIES
      IMPORTED_LOCATION "${OSD_CULL_OPENSUBDIV_GPU_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${OSD_CULL_OPENSUBDIV_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES OpenSubdiv::osdCPU)
  endif()
endif()

# OpenMesh is only needed by the adapters (OFF, PLY, STL, plain OBJ).
find_package(OpenMesh CONFIG QUIET)
