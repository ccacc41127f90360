#pragma once
/// \file patch_clusters.h
/// \brief Clustered, hierarchical culling (Zachmann's lecture, "Clustered Backface Culling"
/// and "Hierarchical Clustered Backface Culling"): patches near in space and in normal form
/// clusters, one test per cluster culls or accepts all of its patches, the rest are tested
/// one by one; sizes from the cost model T = t + (1 - P) R (docs/algorithms/clusters.md).

#include "osd_cull/bound/cone_of_normals.h"
#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/patch/patch_set.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace osd_cull::bound {

/// \brief The lecture's cost model, in units of one per-patch test r = 1.
struct ClusterCostModel {
  /// t: one cluster test relative to one per-patch test. Default 1: a cluster test does
  /// the arithmetic of one per-patch box and cone test (docs/algorithms/clusters.md has the
  /// share of undecided patches for other values and the measured costs).
  double clusterTest = 1.0;
  /// Writing one member's result when the cluster decides (a store and, accepted, an
  /// append to the draw list), relative to one per-patch test.
  double memberWrite = 0.1;
  /// The largest cluster: one invocation of the cluster kernel writes every member.
  uint32_t maxPatches = 64;
};

/// \brief One cluster: its box, its cone and the range of its members.
struct PatchCluster {
  glm::dvec3 boxMin{0.0};  ///< of the members' control points
  glm::dvec3 boxMax{0.0};
  glm::dvec3 axis{0.0, 0.0, 1.0};  ///< A, unit
  double angle = 0.0;              ///< Γ: every member normal lies within Γ of A
  double sinAngle = 1.0;           ///< sin Γ rounded up
  bool coneValid = false;          ///< every member's cone valid and Γ < 85°
  /// The cull region (apex, axis A, sin of cullAngle): inside every member's cull region
  /// with a margin (buildPatchClusters); valid when coneValid.
  glm::dvec3 apex{0.0};
  double cullSinAngle = 1.0;
  uint32_t first = 0;         ///< into PatchClusters::members
  uint32_t bezierCount = 0;   ///< members [first, first + bezierCount) are Bézier patches
  uint32_t gregoryCount = 0;  ///< then the Gregory patches
  uint32_t size() const { return bezierCount + gregoryCount; }
};

/// \brief The clusters of one patch set: each patch in exactly one cluster.
struct PatchClusters {
  std::vector<PatchCluster> clusters;
  std::vector<uint32_t> members;  ///< patch indices, grouped by cluster
  /// The model's expected cost per view of the clustered tests and of testing every patch
  /// (units of one per-patch test).
  double modelCost = 0.0;
  double perPatchCost = 0.0;
};

/// \brief Clusters `patches` for the cone of normals `cones` (one per patch, e.g.
/// buildPatchCones(patches, method); empty: frustum-only clusters, whose cones are
/// invalid). Starts from one cluster per base face (PatchParam face id), and greedily merges
/// neighbouring clusters (sharing a patch corner point) while the cost model says the
/// joint test pays, at most `model.maxPatches` patches a cluster.
/// \throws osd_cull::Error when `cones` is neither empty nor one per patch.
PatchClusters buildPatchClusters(const PatchSet& patches, std::span<const ConeOfNormals> cones,
                                 const ClusterCostModel& model = {});

/// \brief The decision on one cluster (the kernel's codes, shaders/shared/cluster_layout.h).
enum class ClusterVerdict : uint32_t {
  Undecided = 0,         ///< test its members patch by patch
  CulledFrustum = 1,     ///< outside a frustum plane (ClusterResult::plane)
  CulledBackFacing = 2,  ///< the eye in the cull region
  Accepted = 3,          ///< inside the frustum and front-facing: members drawn untested
};

struct ClusterResult {
  ClusterVerdict verdict = ClusterVerdict::Undecided;
  uint32_t plane = 6;  ///< with CulledFrustum: the lowest plane (FrustumPlane) it is outside of
};

/// \brief What the cluster test may decide.
struct ClusterTests {
  bool frustum = true;     ///< the pass runs the frustum test
  bool backPatch = false;  ///< the pass runs a cone back-patch test (cones given)
  /// Cull back-facing clusters whole: only when the members' per-patch test is the cone
  /// test of the clusters' cones on the surface (no drawn-triangle widening), else the cull
  /// might not be one of the per-patch test.
  bool backCull = false;
  bool accept = true;  ///< accept clusters (false with an occlusion stage, which must run)
};

/// \brief The double-precision reference of the cluster kernel (shaders/cull/cluster_cull.comp)
/// with the margins of clip_space.h (kRelativeMargin). A non-finite box, cone or view is
/// Undecided.
ClusterResult testCluster(const PatchCluster& cluster, const CullView& view,
                          const ClusterTests& tests);

}  // namespace osd_cull::bound
