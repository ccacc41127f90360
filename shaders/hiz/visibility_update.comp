#version 450
// Temporal visibility (Niessner & Loop §3): after the cull kernel has decided every patch,
// update its status and build the draw lists. A surviving patch stays VISIBLE if it was
// visible (it was drawn in this frame's first pass) or becomes NEWLY VISIBLE (drawn in the
// second pass); a culled one records the stage that culled it. Survivors are appended to
// the next frame's first-pass list, newly visible ones to this frame's second-pass list
// (Bezier from slot 0, Gregory from slot bezierCount). The tess-factor-0 variant (§5) gets
// full lists instead, every patch in its own slot, flagged kDrawListCulled unless drawn.
#include <shared/draw_layout.h>
#include <shared/visibility_layout.h>

layout(local_size_x = 64) in;

layout(push_constant) uniform Push { VisibilityConstants pc; };
layout(std430, set = 0, binding = kVisBindingResults) readonly buffer Results { uint results[]; };
layout(std430, set = 0, binding = kVisBindingStatus) buffer Status { uint status[]; };
layout(std430, set = 0, binding = kVisBindingNextList) writeonly buffer Next { uint next[]; };
layout(std430, set = 0, binding = kVisBindingNextCounters) buffer NextCounters { uint nextCounters[]; };
layout(std430, set = 0, binding = kVisBindingNewList) writeonly buffer Fresh { uint fresh[]; };
layout(std430, set = 0, binding = kVisBindingNewCounters) buffer FreshCounters { uint freshCounters[]; };
layout(std430, set = 0, binding = kVisBindingNextAll) writeonly buffer NextAll { uint nextAll[]; };
layout(std430, set = 0, binding = kVisBindingNewAll) writeonly buffer FreshAll { uint freshAll[]; };
layout(std430, set = 0, binding = kVisBindingStats) buffer Stats { uint stats[]; };

void main() {
  uint p = gl_GlobalInvocationID.x;
  if (p >= pc.patchCount) return;
  uint stage = results[p] & 0xFu;  // kStage*
  bool survived = stage == kStageNone;
  bool wasVisible = (status[p] & kStatusVisible) != 0u;
  bool newlyVisible = survived && !wasVisible;
  status[p] = survived ? (kStatusVisible | (newlyVisible ? kStatusNewlyVisible : 0u))
                       : (stage << kStatusStageShift);

  bool bezier = p < pc.bezierCount;
  uint base = bezier ? 0u : pc.bezierCount;
  uint counter = bezier ? kListSurvivorsBezier : kListSurvivorsGregory;
  if (survived) {
    next[base + atomicAdd(nextCounters[counter], 1u)] =
        p | (kDrawStatusVisible << kDrawListStatusShift);
    atomicAdd(stats[kStatSurvivors], 1u);
  }
  if (newlyVisible) {
    fresh[base + atomicAdd(freshCounters[counter], 1u)] =
        p | (kDrawStatusNewlyVisible << kDrawListStatusShift);
    atomicAdd(stats[kStatNewlyVisible], 1u);
  }
  nextAll[p] = survived ? p | (kDrawStatusVisible << kDrawListStatusShift) : p | kDrawListCulled;
  freshAll[p] = newlyVisible ? p | (kDrawStatusNewlyVisible << kDrawListStatusShift)
                             : p | kDrawListCulled;
  if (stage == kStageFrustum) atomicAdd(stats[kStatCulledFrustum], 1u);
  if (stage == kStageBackPatch) atomicAdd(stats[kStatCulledBackPatch], 1u);
  if (stage == kStageOcclusion) atomicAdd(stats[kStatCulledOcclusion], 1u);
}
