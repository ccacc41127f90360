#pragma once
/// \file load_mesh.h
/// \brief Reads mesh files into a CageMesh (to be refined) or Bézier patches (used as is).
///
/// Formats: OBJ with OpenSubdiv tag lines (`t crease`, `t corner`, `t interpolateboundary`,
/// `t hole`, `t smoothtriangles`, `t creasemethod`, `t facevaryinginterpolateboundary`);
/// OFF, PLY, STL through OpenMesh; BPT Bézier patch files.
/// Errors are osd_cull::Error with "FILE:LINE: problem".

#include "osd_cull/patch/cage_mesh.h"
#include "osd_cull/patch/patch_set.h"

#include <filesystem>
#include <optional>

namespace osd_cull::adapters {

/// \brief Options of loadCage().
struct LoadOptions {
  /// Scheme to use; if unset, the file-name prefix decides (catmark_, loop_, bilinear_),
  /// else Catmull-Clark.
  std::optional<Scheme> scheme;
};

/// \brief True for files read as Bézier patches rather than cages (".bpt").
bool isBezierPatchFile(const std::filesystem::path& path);

/// \brief Reads a cage from OBJ (with OpenSubdiv tags), OFF, PLY or STL. The result is
/// validated (see osd_cull::validate).
CageMesh loadCage(const std::filesystem::path& path, const LoadOptions& options = {});

/// \brief Reads a BPT file: first line the patch count, per patch a line "3 3" and 16
/// lines "x y z" (u fastest). Returns a PatchSet of Bézier patches with origin Input and
/// PatchParam face id = patch index.
PatchSet loadBezierPatches(const std::filesystem::path& path);

}  // namespace osd_cull::adapters
