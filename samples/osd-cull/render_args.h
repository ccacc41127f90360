#pragma once
/// \file render_args.h
/// \brief The parsed options of `osd-cull render`, shared by its mesh form (cmd_render.cpp)
/// and its scene form (scene_render.cpp).

#include "cull_options.h"
#include "displacement_args.h"
#include "mesh_source.h"
#include "plan_options.h"

#include "osd_cull/vk/context.h"

#include <cstdint>
#include <optional>
#include <string>

namespace osd_cull::cli {

/// \brief `osd-cull render` as given; empty optionals take the form's own default.
struct RenderArgs {
  MeshSource source;
  PatchOptions patchOptions;
  CullArgs cull;                  ///< cull.mode empty: not given (mesh: none; scene: all)
  PlanArgs plan;                  ///< the mesh form: --plan auto plans when --cull is not given
  DisplacementArgs displacement;  ///< the mesh form only
  vulkan::ContextOptions device;
  std::string out;                 ///< required by the mesh form
  std::optional<uint32_t> width;   ///< mesh: 640; scene: its own
  std::optional<uint32_t> height;  ///< mesh: 480; scene: its own
  uint32_t tess = 4;
  double adaptive = 0.0;  ///< 0: uniform tessellation
  std::string camera;
  std::optional<uint32_t> frames;  ///< mesh: 1; scene: its frameCount
  double orbitDegrees = 0.0;
  std::string outDir;
  bool ids = false;
  bool debugColors = false;
  std::string stats;
  std::string occluders;
  bool statusView = false;
  std::string pyramidDir;
  bool compare = false;  ///< scene only
  bool verbose = false;  ///< every plan with each stage's reason, not its headline alone
};

}  // namespace osd_cull::cli
