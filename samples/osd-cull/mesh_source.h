#pragma once
/// \file mesh_source.h
/// \brief The MESH argument shared by osd-cull subcommands: a file or the built-in mesh.

#include "command.h"

#include "osd_cull/patch/adaptive_patches.h"
#include "osd_cull/patch/cage_mesh.h"
#include "osd_cull/patch/patch_set.h"

#include <optional>
#include <string>

namespace osd_cull::cli {

/// \brief What the user asked to load.
struct MeshSource {
  std::optional<std::string> path;  ///< empty: the built-in default mesh
  std::optional<Scheme> scheme;     ///< --scheme
};

/// \brief A loaded mesh: a cage to refine, or Bézier patches used as they are.
struct LoadedMesh {
  std::string name;
  std::optional<CageMesh> cage;
  std::optional<PatchSet> bezier;
};

/// \brief Reads the optional positional MESH and `--scheme`; more than one positional is
/// an error.
MeshSource meshSourceFromArgs(Args& args);

/// \brief Reads `--level N` (0..10, default 2) and `--endcap gregory|bspline` (default
/// gregory) into patch options.
PatchOptions patchOptionsFromArgs(Args& args);

/// \brief Loads the mesh (adapters/) or generates the built-in one.
LoadedMesh loadMeshSource(const MeshSource& source);

}  // namespace osd_cull::cli
