// The clustered cull (osd_cull/bound/patch_clusters.h, shaders/cull/cluster_cull.comp): its
// bindings in the cull set (set 0 of shared/cull_layout.h) and the layout of its buffers,
// shared by C++ and GLSL so they cannot drift.
#ifndef OSD_CULL_SHARED_CLUSTER_LAYOUT_H
#define OSD_CULL_SHARED_CLUSTER_LAYOUT_H
#include "glsl_compat.h"

OSD_CULL_SHARED_BEGIN

// uint clusterWork[]: kClusterWorkHeader uints, then the patches of undecided clusters.
//   [0..2] VkDispatchIndirectCommand of the per-patch kernel (x: groups, y = z = 1)
//   [3]    patches listed (per-patch kernel invocations)
//   [4..6] clusters culled, accepted, undecided (this pass)
//   [8]    clusters; [9] patches per workgroup of the per-patch kernel; [10] kClusterFlag*
OSD_CULL_CONST uint kCullBindingClusterWork = 12u;
// vec4 clusters[]: kClusterVec4s per cluster:
//   (box min.xyz, sin Γ rounded up), (box max.xyz, sin of the cull angle rounded up),
//   (cull-region apex.xyz, 1 when the cone is valid else 0), (axis.xyz, 0)
OSD_CULL_CONST uint kCullBindingClusters = 13u;
// uint clusterMembers[]: per cluster uvec4 (first member, Bezier members, Gregory members, 0),
// then the members (patch indices, Bezier first in each cluster) from uint 4 * clusters.
OSD_CULL_CONST uint kCullBindingClusterMembers = 14u;

OSD_CULL_CONST uint kClusterWorkHeader = 12u;
OSD_CULL_CONST uint kClusterWorkListed = 3u;
OSD_CULL_CONST uint kClusterWorkCulled = 4u;
OSD_CULL_CONST uint kClusterWorkAccepted = 5u;
OSD_CULL_CONST uint kClusterWorkUndecided = 6u;
OSD_CULL_CONST uint kClusterWorkClusters = 8u;
OSD_CULL_CONST uint kClusterWorkPatchesPerGroup = 9u;
OSD_CULL_CONST uint kClusterWorkFlags = 10u;
OSD_CULL_CONST uint kClusterVec4s = 4u;

OSD_CULL_CONST uint kClusterFlagFrustum = 1u;    // the pass runs the frustum test
OSD_CULL_CONST uint kClusterFlagBackPatch = 2u;  // a cone back-patch test: front-facing accepts
OSD_CULL_CONST uint kClusterFlagBackCull = 4u;   // back-facing clusters culled whole
OSD_CULL_CONST uint kClusterFlagAccept = 8u;     // decided clusters may be accepted

OSD_CULL_CONST uint kClusterGroupSize = 64u;

// Bits 24-25 of a result code (shared/cull_layout.h): the cluster test decided the patch.
OSD_CULL_CONST uint kResultShiftCluster = 24u;
OSD_CULL_CONST uint kResultClusterCulled = 1u;
OSD_CULL_CONST uint kResultClusterAccepted = 2u;

OSD_CULL_SHARED_END
#endif
