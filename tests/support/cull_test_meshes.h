#pragma once
/// \file cull_test_meshes.h
/// \brief Meshes for the cull tests: shared-data shapes turned into patches with their
/// per-mesh back-patch decision, and a summary check of CullVerifier totals.

#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/frame/verify/cull_verification.h"
#include "osd_cull/patch/patch_set.h"

#include <filesystem>
#include <string>

namespace osd_cull::test {

/// \brief Patches of a mesh and whether back-patch culling is valid on it.
struct CullMesh {
  std::string name;
  PatchSet patches;
  bound::BackPatchValidity validity;
};

/// \brief Loads a cage file (adapters::loadCage), extracts its patches at `level` and
/// decides back-patch validity from its topology and signed volume.
CullMesh loadCullMesh(const std::filesystem::path& path, int level = 2);

/// \brief Every method's totals show no violation (gtest failures otherwise): no GPU cull
/// outside the double reference, no visible sample on the dense sampling, no pixel lost in
/// the image, and no culled patch with pixels in the oracle (back-patch methods respect the
/// drawn triangles by default, bound/drawn_triangles.h).
void expectNoViolations(const frame::CullVerifier& verifier, const std::string& context);

/// \brief The totals of one method (gtest failure and a dummy when absent).
const frame::MethodTotals& totalsOf(const frame::CullVerifier& verifier, const std::string& name);

}  // namespace osd_cull::test
