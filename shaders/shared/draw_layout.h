// Push constants and buffer layouts of the patch and triangle draw pipelines
// (shaders/patch/*, shaders/mesh/*), shared by C++ (osd_cull/frame) and GLSL.
#ifndef OSD_CULL_SHARED_DRAW_LAYOUT_H
#define OSD_CULL_SHARED_DRAW_LAYOUT_H
#include "glsl_compat.h"

OSD_CULL_SHARED_BEGIN

// Descriptor bindings of the patch draw set (set 0).
OSD_CULL_CONST uint kBindingPoints = 0;  // control points: common/control_points.glsl
OSD_CULL_CONST uint kBindingParams = 1;  // uint params[]: Far::PatchParam field0, field1 per patch
OSD_CULL_CONST uint kBindingDrawList = 2;  // uint drawList[]: patch index per draw slot
// uvec2 tessLevels[]: the adaptive levels of every patch, per level slot (GpuPatchSet::
// tessLevels(), written by patch/tess_levels.comp, packed by packTessLevels).
OSD_CULL_CONST uint kBindingTessLevels = 3;

// DrawConstants.mode
OSD_CULL_CONST uint kTessUniform = 0u;
OSD_CULL_CONST uint kTessAdaptive = 1u;

// DrawConstants.flags
OSD_CULL_CONST uint kFlagDebugColors = 1u;      // color each patch by a hash of its index
OSD_CULL_CONST uint kFlagStatusColors = 2u;     // color each patch by its draw-list status field
OSD_CULL_CONST uint kFlagFrontWinsTies = 4u;    // push back-facing fragments back (patch.frag)
OSD_CULL_CONST uint kFlagPatchTypeColors = 8u;  // regular/boundary/corner/Gregory (patch.tese)
// No clamp of fragment depth to the control points (patch.tesc): for measuring what the clamp
// costs only; Hi-Z occlusion culls of such a draw are not proven (docs/algorithms/occlusion.md).
OSD_CULL_CONST uint kFlagNoDepthClamp = 16u;
// Displaced draws, adaptive levels (frame::DisplacedTessellation; patch.tesc): neither
// bit adds each edge's own displacement variation; kFlagTessIgnoreDisplacement adds none;
// kFlagTessPerPatchDisplacement adds the patch's largest to every edge (cracks: tests).
OSD_CULL_CONST uint kFlagTessIgnoreDisplacement = 32u;
OSD_CULL_CONST uint kFlagTessPerPatchDisplacement = 64u;
// Adaptive levels are read from tessLevels[levelBase + patch] (written for this view by the
// levels pass, frame::TessLevelsPass) instead of computed by the control shader: the cull
// kernel's drawn-triangle test then knows the drawn levels exactly
// (docs/algorithms/drawn-triangles.md, "Exact adaptive levels").
OSD_CULL_CONST uint kFlagTessLevelsFromBuffer = 128u;

// A draw-list entry: the patch index in the low 28 bits, a status for the debug view in
// bits 28-30 (kDrawStatus*) and, in bit 31, "culled": the control shader sets every
// tessellation factor to 0 (the tess-factor-0 variant of Niessner & Loop §5), skipping the
// factor computation. Plain indices (flags 0) draw as before.
OSD_CULL_CONST uint kDrawListPatchMask = 0x0FFFFFFFu;
OSD_CULL_CONST uint kDrawListStatusShift = 28u;
OSD_CULL_CONST uint kDrawListCulled = 0x80000000u;
OSD_CULL_CONST uint kDrawStatusNone = 0u;
OSD_CULL_CONST uint kDrawStatusVisible = 1u;       // drawn in the first pass
OSD_CULL_CONST uint kDrawStatusNewlyVisible = 2u;  // drawn in the second pass
OSD_CULL_CONST uint kDrawStatusFrustum = 3u;       // culled by the view frustum
OSD_CULL_CONST uint kDrawStatusBackPatch = 4u;     // culled as back-facing
OSD_CULL_CONST uint kDrawStatusOccluded = 5u;      // culled by the Hi-Z test

// Item-buffer values: 0 is background, patch p of a set with itemBase b writes b + p + 1,
// triangle occluders write kItemOccluder.
OSD_CULL_CONST uint kItemBackground = 0u;
OSD_CULL_CONST uint kItemOccluder = 0xFFFFFFFFu;

// 128 bytes: the minimum push-constant size every Vulkan device supports.
struct DrawConstants {
  mat4 viewProjection;  // world to clip space (Vulkan: y down, depth 0..1)
  vec4 eye;             // xyz: camera position (world); w: pixels per segment (adaptive)
  vec4 viewport;        // xy: width, height in pixels; z: uniform level; w: max level
  uint mode;            // kTessUniform or kTessAdaptive
  uint bezierCount;     // patches [0, bezierCount) are Bezier, the rest Gregory
  uint pointStride;     // floats between consecutive control points (>= 3)
  uint pointOffset;     // float index of control point 0
  uint flags;           // kFlag* bits
  uint itemBase;        // added to the item-buffer value (triangles: the value written)
  uint levelBase;       // kFlagTessLevelsFromBuffer: patch 0's entry in tessLevels[]
  uint levelCount;      // the levels pass (tess_levels.comp): patches to level; draws: 0
};

OSD_CULL_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(osd_cull::shader::DrawConstants) == 128);
#endif
#endif
