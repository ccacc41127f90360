#pragma once
/// \file back_patch_validity.h
/// \brief Whether back-patch culling may be used on a mesh at all.
///
/// A back-facing patch is invisible only when something in front hides it: the surface
/// must be closed (a solid, Zachmann's lecture "Back-Face Culling: only works with solids")
/// and consistently oriented with its normals Bu x Bv pointing out. On open meshes
/// (boundaries, holes, the teapot's rims) the inside of the surface can be seen through the
/// opening, so back-patch culling is switched off for the whole mesh, with the reason.

#include "osd_cull/patch/cage_mesh.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"

#include <optional>
#include <string>

namespace osd_cull::bound {

/// \brief The decision for one mesh: enabled, or disabled with the reason (for reports).
struct BackPatchValidity {
  bool enabled = false;
  std::string reason;
};

/// \brief Decides from the topology of the cage, and its signed volume when given:
/// disabled if the cage has no faces, boundary edges, holes, non-manifold edges (which in
/// OpenSubdiv include edges whose faces disagree on orientation) or non-manifold vertices
/// (orientation around them is not checked), or if the signed volume is negative (faces
/// clockwise seen from outside: the normals point in), zero or not finite.
/// Without a signed volume, a closed manifold cage is enabled and the reason says that
/// outward orientation was assumed.
BackPatchValidity backPatchValidity(const TopologySummary& topology,
                                    std::optional<double> signedVolume = std::nullopt);

/// \brief The patches of a cage and whether back-patch culling may be used on them: what
/// every program that culls a cage needs first (the CLI, the benchmarks, the tests).
struct CullablePatches {
  PatchExtraction extraction;
  BackPatchValidity backPatch;
};

/// \brief Extracts the patches of `cage` and decides the back-patch validity from the same
/// refiner's base level and the cage's signed volume (one refiner, not two).
/// \throws osd_cull::Error as extractPatches().
CullablePatches cullablePatches(const CageMesh& cage, const PatchOptions& options = {});

/// \brief The signed volume enclosed by the cage's faces (divergence theorem, each face
/// fanned from its first vertex): positive when faces are counter-clockwise seen from
/// outside. Faces tagged as holes are skipped. Meaningful for closed cages only.
double signedVolume(const CageMesh& mesh);

}  // namespace osd_cull::bound
