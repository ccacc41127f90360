#pragma once
/// \file verify_args.h
/// \brief The parsed options of `osd-cull verify`, shared by its mesh form (cmd_verify.cpp)
/// and its scene form (scene_verify.cpp).

#include "displacement_args.h"
#include "mesh_source.h"

#include "osd_cull/vk/context.h"

#include <cstdint>
#include <optional>
#include <string>

namespace osd_cull::cli {

/// \brief `osd-cull verify` as given; empty optionals take the form's own default.
struct VerifyArgs {
  MeshSource source;
  PatchOptions patchOptions;
  vulkan::ContextOptions device;
  DisplacementArgs displacement;   ///< the mesh form only
  std::optional<uint32_t> views;   ///< mesh: 100; scene: 4 per frame
  std::optional<uint32_t> frames;  ///< scene only: 2
  uint64_t seed = 1;
  std::string viewSet = "sphere";
  std::string methods;  ///< empty: the form's default list
  uint32_t tess = 4;
  double adaptive = 0.0;  ///< > 0: adaptive tessellation, PIXELS per segment (the mesh form)
  std::optional<uint32_t> width;   ///< mesh: 256; scene: 128
  std::optional<uint32_t> height;  ///< mesh: 256; scene: 128
  double fov = 40.0;
  uint32_t referenceEvery = 1;
  bool noOracle = false;
  int sample = 0;
  bool imageCheck = false;
  bool hizFull = false;
  bool hizTight = false;
  std::string json;
  bool surfaceExact = false;
  bool drawnEnumerate = false;
  bool clusters = false;
};

}  // namespace osd_cull::cli
