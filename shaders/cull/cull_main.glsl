// The cull kernel: one dispatch over all patches of a GpuPatchSet, for every instance of it
// (invocation = (instance, patch), shared/cull_layout.h CullInstance), runs the enabled stages
// cheapest first (frustum, back-patch, occlusion), writes each patch's result code and
// appends survivors to the compact draw list (Bezier from slot 0, Gregory from slot
// bezierCount). The host composes the source (frame/cull_pass.cpp):
//   CULL_LANES        threads per patch (1, or 16 for tangent-plane-16)
//   CULL_FRUSTUM      1: run the frustum test (frustum.glsl)
//   CULL_BACK_PATCH   1: a back-patch file defines
//                     uint backPatchVerdict(uint patchIndex, uint lane, uint slot, bool run)
//                     returning a bound::BackPatchVerdict (0 = culled) or 0xFF when !run;
//                     called by every invocation (multi-lane versions use barriers)
//   CULL_OCCLUSION    1: an occlusion file defines
//                     uint occlusionVerdict(uint patchIndex, PatchClipBounds bounds)
//                     returning 0 (culled: occluded) or a non-zero reason to keep; called by
//                     one thread per patch that survived the earlier stages; its resources
//                     live in descriptor set 1 (per-view values in its own uniform buffer)
//   CULL_DRAWN        1: back-patch culls respect the drawn triangles (drawn_triangles.glsl)
//   CULL_DRAWN_ENUMERATE 1 (with CULL_DRAWN_LISTED): a patch the worst-case bound keeps is
//                     culled when every triangle the tessellator can draw for it faces away
//                     (drawn_triangle_set.glsl, exact levels only: uniform or precomputed),
//                     for patches whose outer levels are at most CULL_DRAWN_LIST_LEVEL
//   CULL_DRAWN_DEFER  1 (with CULL_DRAWN): a patch the worst-case bound keeps but the
//                     listing could decide (drawnListable) is not finished here: its code so
//                     far goes to results[] and the patch to deferred[] for the
//                     listed-triangle pass. On lavapipe the listing's code slows every
//                     invocation of a kernel that contains it (its arrays live in memory per
//                     SIMD lane), even where it never runs: 600-1000 ns a patch against 255
//                     without (docs/results/cull-kernel-floor.md), so it runs only on the
//                     candidates, compacted.
//   CULL_DRAWN_LISTED 1: the listed-triangle pass itself, over deferred[] (an indirect
//                     dispatch after the cull kernel): the listing (CULL_DRAWN_ENUMERATE),
//                     then the code and the draw list, as the cull kernel would have
//                     finished them. The cull kernel runs the occlusion stage before it
//                     defers a candidate, so a hidden patch is never listed (it is culled
//                     by occlusion, where the reference names back-patch: same survivors). One pass per patch type
//                     (CULL_DRAWN_LISTED_GREGORY 0: the Bezier list, 1: the Gregory list),
//                     so that neither evaluates the other type's surface.
//   CULL_CLUSTERS     1: only the patches the cluster test left undecided
//                     (cluster_cull.comp lists them in clusterWork), one instance, by an
//                     indirect dispatch
// and includes the stage files before this one.
#include "frustum.glsl"
#if CULL_CLUSTERS
#include <shared/cluster_layout.h>
layout(std430, set = 0, binding = kCullBindingClusterWork) readonly buffer Work {
  uint clusterWork[];
};
#endif
#if CULL_DRAWN && CULL_DRAWN_ENUMERATE
#include "drawn_triangle_set.glsl"
#endif

#if CULL_DRAWN_DEFER || CULL_DRAWN_LISTED
layout(std430, set = 0, binding = kCullBindingDeferred) buffer Deferred { uint deferred[]; };

// The first word of the Bezier or the Gregory candidates' list (shared/cull_layout.h).
uint deferredList(bool bezier) {
  return bezier ? 0u : kDeferredHeader + 2u * instanceHeader.x * pcView.bezierCount;
}
#endif

layout(local_size_x = kCullGroupSize) in;

// Appends a surviving patch of the instance whose results begin at `base` to its draw list.
void appendSurvivor(uint base, uint counterBase, uint patchIndex) {
  if (isBezier(patchIndex)) {
    drawList[base + atomicAdd(counters[counterBase + kCounterSurvivorsBezier], 1u)] = patchIndex;
  } else {
    drawList[base + pc.bezierCount +
             atomicAdd(counters[counterBase + kCounterSurvivorsGregory], 1u)] = patchIndex;
  }
}

#if CULL_DRAWN_LISTED
void main() {
  const uint list = deferredList(CULL_DRAWN_LISTED_GREGORY == 0);
  const uint count = deferred[list + kDeferredCount];
  const uint stride = gl_NumWorkGroups.x * kCullGroupSize;
  for (uint i = gl_GlobalInvocationID.x; i < count; i += stride) {
    const uint instance = deferred[list + kDeferredHeader + 2u * i];
    const uint patchIndex = deferred[list + kDeferredHeader + 2u * i + 1u];
    loadInstance(instance);
    const uint base = instance * pc.patchCount;
    uint result = results[base + patchIndex];
    // The occlusion stage ran in the cull kernel (the candidates are not hidden).
    if (drawnTrianglesFaceAway(patchIndex)) {
      result = withField(result, kResultShiftBackPatch, 8u, kVerdictBackFacing);
      result = withStage(result, kStageBackPatch);
    }
    results[base + patchIndex] = result;
    if (resultStage(result) == kStageNone)
      appendSurvivor(base, instance * kCounterCount, patchIndex);
  }
}
#else

const uint kLanes = uint(CULL_LANES);
const uint kPatchesPerGroup = kCullGroupSize / kLanes;
#if CULL_LANES > 1
shared uint sResult[kPatchesPerGroup];
#endif

void main() {
  const uint lane = gl_LocalInvocationIndex % kLanes;
  const uint slot = gl_LocalInvocationIndex / kLanes;
  // The host spreads more than maxComputeWorkGroupCount[0] groups over y (vk/limits.h).
  // Issue 10: the groups of instance i follow those of instance i - 1, each instance
  // covering its patches with ceil(patchCount / kPatchesPerGroup) groups, so a whole
  // workgroup belongs to one instance (the multi-lane barriers stay uniform).
  const uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  const uint groupsPerInstance = (pcView.patchCount + kPatchesPerGroup - 1u) / kPatchesPerGroup;
  const uint instance = group / max(groupsPerInstance, 1u);
  const bool instanceInRange = instance < instanceHeader.x;
  loadInstance(instanceInRange ? instance : 0u);
#if CULL_DISPLACED
  dview = dviews[instanceInRange ? instance : 0u];
#endif
#if CULL_CLUSTERS
  const uint listed = group * kPatchesPerGroup + slot;
  const bool inRange = instanceInRange && listed < clusterWork[kClusterWorkListed];
  const uint patchIndex = inRange ? clusterWork[kClusterWorkHeader + listed] : 0u;
#else
  const uint patchIndex = (group - instance * groupsPerInstance) * kPatchesPerGroup + slot;
  const bool inRange = instanceInRange && patchIndex < pc.patchCount;
#endif
  const uint base = instance * pc.patchCount;  // the instance's results and draw list
  const uint counterBase = instance * kCounterCount;
  uint result = kResultInitial;
  PatchClipBounds bounds;
  bounds.finite = false;
  bounds.hasNdcBox = false;

#if CULL_FRUSTUM || CULL_OCCLUSION
  if (inRange && lane == 0u) bounds = patchClipBounds(patchIndex);
#endif
#if CULL_FRUSTUM
  if (inRange && lane == 0u) {
    uint f = frustumCode(bounds);
    result = withField(result, kResultShiftFrustum, 4u, f);
    if (f < kFrustumInside) result = withStage(result, kStageFrustum);
  }
#endif

#if CULL_BACK_PATCH
#if CULL_LANES > 1
  if (lane == 0u) sResult[slot] = result;
  memoryBarrierShared();
  barrier();
  result = sResult[slot];
#endif
  const bool runBackPatch = inRange && resultStage(result) == kStageNone;
  uint b = backPatchVerdict(patchIndex, lane, slot, runBackPatch);
#if CULL_DRAWN && CULL_DRAWN_DEFER
  const bool defer =
      runBackPatch && lane == 0u && b == kVerdictDrawnTriangles && drawnListable(patchIndex);
#endif
  if (runBackPatch) {
    result = withField(result, kResultShiftBackPatch, 8u, b);
    if (b == kVerdictBackFacing) result = withStage(result, kStageBackPatch);
  }
#endif

  if (!inRange || lane != 0u) return;
#if CULL_OCCLUSION
  // Before the listed-triangle pass is given a candidate: a patch whose box is hidden needs
  // no triangle listed (most back-facing patches of a closed surface are also behind its
  // front; listing them cost 38 ms of a 285 ms BigGuy frame at tess 16). Such a patch is
  // culled by the occlusion stage, whose verdict needs nothing of the back-patch test.
  if (resultStage(result) == kStageNone) {
    uint o = occlusionVerdict(patchIndex, bounds);
    result = withField(result, kResultShiftOcclusion, 8u, o);
    if (o == 0u) result = withStage(result, kStageOcclusion);
  }
#endif
#if CULL_DRAWN && CULL_DRAWN_DEFER
  if (defer && resultStage(result) == kStageNone) {  // finished by the listed-triangle pass
    results[base + patchIndex] = result;
    const uint list = deferredList(isBezier(patchIndex));
    const uint i = atomicAdd(deferred[list + kDeferredCount], 1u);
    deferred[list + kDeferredHeader + 2u * i] = instance;
    deferred[list + kDeferredHeader + 2u * i + 1u] = patchIndex;
    // The groups the pass needs, ceil(count / kCullGroupSize), from the first candidate of
    // each group (the indices are 0..count-1): one atomic per group, not per candidate.
    if (i % kCullGroupSize == 0u)
      atomicMax(deferred[list], min(i / kCullGroupSize + 1u, kDeferredMaxGroups));
    return;
  }
#endif

  results[base + patchIndex] = result;
  if (resultStage(result) == kStageNone) appendSurvivor(base, counterBase, patchIndex);
}
#endif
