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
  /// Vertices no face used, dropped before refinement (adapters::dropUnusedVertices): the
  /// file had cage->vertexCount() + droppedVertices.
  size_t droppedVertices = 0;
};

/// \brief Declares the optional positional MESH and `--scheme S`, filled into `source`
/// when the line is parsed; more than one MESH is a usage error.
void addMeshOptions(CLI::App& app, MeshSource& source);

/// \brief Declares `--level N` (0..10, default 2) and `--endcap gregory|bspline` (default
/// gregory), filled into `options` when the line is parsed.
void addPatchOptions(CLI::App& app, PatchOptions& options);

/// \brief Loads the mesh (adapters/) or generates the built-in one. Unused vertices of a
/// cage are dropped (counted in LoadedMesh::droppedVertices): nothing the commands do
/// depends on them, and millions of them would cost refinement seconds and gigabytes.
LoadedMesh loadMeshSource(const MeshSource& source);

}  // namespace osd_cull::cli
