// Buffers and push constants of the temporal visibility pass (Niessner & Loop §3, §5):
// shaders/hiz/visibility_update.comp (status bits, compact draw lists) and
// shaders/hiz/visibility_draws.comp (indirect draw commands), shared by C++
// (osd_cull/frame/visibility_buffer, cull_frame) and GLSL.
#ifndef OSD_CULL_SHARED_VISIBILITY_LAYOUT_H
#define OSD_CULL_SHARED_VISIBILITY_LAYOUT_H
#include "cull_layout.h"
#include "glsl_compat.h"

OSD_CULL_SHARED_BEGIN

// Status of one patch, one uint per patch and view (the paper's two flags, §5):
OSD_CULL_CONST uint kStatusVisible = 1u;  // survived the last cull: drawn in the next first pass
OSD_CULL_CONST uint kStatusNewlyVisible = 2u;  // survived, but was not visible before: drawn in
                                               // this frame's second pass
OSD_CULL_CONST uint kStatusStageShift = 4u;    // bits 4-7: the stage that culled it

// The stage bits are the cull kernel's kStage* (shared/cull_layout.h): the low 4 bits of its
// per-patch result code, kStageNone when the patch survived.

// Counters of one draw list (survivors per type, then indirect draw counts per type read by
// vkCmdDrawIndirectCount at byte offset 4 * kListDraws*).
OSD_CULL_CONST uint kListSurvivorsBezier = 0u;
OSD_CULL_CONST uint kListSurvivorsGregory = 1u;
OSD_CULL_CONST uint kListDrawsBezier = 2u;
OSD_CULL_CONST uint kListDrawsGregory = 3u;
OSD_CULL_CONST uint kListCounterCount = 4u;

// Per-frame statistics counters (stats[]).
OSD_CULL_CONST uint kStatCulledFrustum = 0u;
OSD_CULL_CONST uint kStatCulledBackPatch = 1u;
OSD_CULL_CONST uint kStatCulledOcclusion = 2u;
OSD_CULL_CONST uint kStatNewlyVisible = 3u;
OSD_CULL_CONST uint kStatSurvivors = 4u;
OSD_CULL_CONST uint kStatCount = 8u;

// Bindings of visibility_update.comp (set 0).
OSD_CULL_CONST uint kVisBindingResults = 0u;   // uint results[]: cull result per patch
OSD_CULL_CONST uint kVisBindingStatus = 1u;    // uint status[]: read last frame's, write new
OSD_CULL_CONST uint kVisBindingNextList = 2u;  // uint next[]: survivors, next frame's first pass
OSD_CULL_CONST uint kVisBindingNextCounters = 3u;  // uint nextCounters[kListCounterCount]
OSD_CULL_CONST uint kVisBindingNewList =
    4u;  // uint fresh[]: newly visible, this frame's second pass
OSD_CULL_CONST uint kVisBindingNewCounters = 5u;  // uint freshCounters[kListCounterCount]
OSD_CULL_CONST uint kVisBindingNextAll =
    6u;  // uint nextAll[]: every patch, culled flag unless survived
OSD_CULL_CONST uint kVisBindingNewAll =
    7u;  // uint freshAll[]: every patch, culled flag unless newly visible
OSD_CULL_CONST uint kVisBindingStats = 8u;  // uint stats[kStatCount]

// Bindings of visibility_draws.comp (set 0).
OSD_CULL_CONST uint kDrawsBindingCounters = 0u;
OSD_CULL_CONST uint kDrawsBindingCommands = 1u;  // uvec4 commands[]: VkDrawIndirectCommand

OSD_CULL_CONST uint kVisGroupSize = 64u;

struct VisibilityConstants {
  uint patchCount;  // patches [0, bezierCount) are Bezier, the rest Gregory
  uint bezierCount;
  uint chunkBezier;  // patches per indirect draw command (draw_chunks.h batch limits)
  uint chunkGregory;
};

OSD_CULL_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(osd_cull::shader::VisibilityConstants) == 16);
#endif
#endif
