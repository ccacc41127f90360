#pragma once
/// \file load_mesh.h
/// \brief Reads mesh files into a CageMesh (to be refined) or Bézier patches (used as is).
///
/// Formats: OBJ with OpenSubdiv tag lines (`t crease`, `t corner`, `t interpolateboundary`,
/// `t hole`, `t smoothtriangles`, `t creasemethod`, `t facevaryinginterpolateboundary`; see
/// obj_tags.h for their meaning); OFF, ASCII and binary (own reader: exact face lists and
/// line numbers); PLY and STL, ASCII and binary, through OpenMesh's readers; BPT Bézier
/// patch files. Errors are osd_cull::Error with "FILE:LINE: problem" ("FILE: problem" where the
/// format has no lines); a reader never crashes, hangs or allocates what a header claims
/// before checking it against the file size.
///
/// Unusual but legal topology (faces that repeat a vertex, unused vertices, edges with more
/// than two faces, inconsistent orientation) is passed to OpenSubdiv unchanged and
/// described in CageMesh::notes; osd_cull::summarize() gives OpenSubdiv's counts.

#include "osd_cull/patch/cage_mesh.h"
#include "osd_cull/patch/patch_set.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace osd_cull::adapters {

/// \brief Options of loadCage().
struct LoadOptions {
  /// Scheme to use; if unset, the file-name prefix decides (catmark_, loop_, bilinear_),
  /// else Catmull-Clark.
  std::optional<Scheme> scheme;
  /// OBJ only: reverse every face's winding (first vertex kept), as OpenSubdiv's regression
  /// harness does for shapes modelled left-handed (catmark_lefthanded).
  bool leftHanded = false;
};

/// \brief Extensions loadCage() reads in this build (lower case, with the dot).
std::vector<std::string> cageFileExtensions();

/// \brief True for files read as Bézier patches rather than cages (".bpt").
bool isBezierPatchFile(const std::filesystem::path& path);

/// \brief Reads a cage from OBJ (with OpenSubdiv tags), OFF, PLY or STL, chosen by the file
/// extension (case-insensitive). The scheme is options.scheme, else the file-name prefix
/// (catmark_, loop_, bilinear_), else Catmull-Clark; without tags the boundary rule is
/// edge-only, as in OpenSubdiv's regression harness. The result is validated (see
/// osd_cull::validate) and carries notes on what the reader ignored or found unusual.
/// \throws osd_cull::Error naming the file, the line where there is one, and the problem.
CageMesh loadCage(const std::filesystem::path& path, const LoadOptions& options = {});

/// \brief Reads a BPT file: first line the patch count, per patch a line "3 3" and 16
/// lines "x y z" (u fastest). Returns a PatchSet of Bézier patches with origin Input and
/// PatchParam face id = patch index.
PatchSet loadBezierPatches(const std::filesystem::path& path);

}  // namespace osd_cull::adapters
