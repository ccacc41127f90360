// Push constants, bindings and the per-patch result code of the cull pass
// (shaders/cull/*, osd_cull/frame/cull_pass, osd_cull/bound/cull_reference), shared by C++
// and GLSL so they cannot drift.
#ifndef OSD_CULL_SHARED_CULL_LAYOUT_H
#define OSD_CULL_SHARED_CULL_LAYOUT_H
#include "glsl_compat.h"

OSD_CULL_SHARED_BEGIN

// Descriptor bindings of the cull set (set 0). Set 1 belongs to the occlusion stage, when one
// is enabled (CullMethod::stageBindings).
OSD_CULL_CONST uint kCullBindingPoints = 0u;    // GpuPatchSet::pointBinding(): control_points.glsl
OSD_CULL_CONST uint kCullBindingCones = 1u;     // vec4 cones[]: kConeVec4s per patch (PatchCone)
OSD_CULL_CONST uint kCullBindingResults = 2u;   // uint results[]: one result code per patch
OSD_CULL_CONST uint kCullBindingDrawList = 3u;  // uint drawList[]: survivors, Bezier from slot 0,
                                                // Gregory from slot bezierCount
OSD_CULL_CONST uint kCullBindingCounters = 4u;  // uint counters[kCounterCount]
OSD_CULL_CONST uint kCullBindingCommands = 5u;  // uvec4 commands[]: VkDrawIndirectCommand
OSD_CULL_CONST uint kCullBindingParams = 7u;    // uint params[]: GpuPatchSet::params(), read
                                                // for transition edges (drawn-triangle bound)
OSD_CULL_CONST uint kCullBindingDisplacedView = 8u;  // DisplacedView: per-view matrices of
                                                     // the displaced bounds (CULL_DISPLACED)
OSD_CULL_CONST uint kCullBindingInstances = 9u;      // CullInstances: the instances culled in
                                                     // one dispatch (their view · model)
OSD_CULL_CONST uint kCullBindingTable = 6u;          // uvec2 table[]: the method's constant table
OSD_CULL_CONST uint kCullBindingTessLevels = 10u;  // uvec2 tessLevels[]: GpuPatchSet::tessLevels()
OSD_CULL_CONST uint kCullBindingBoxes = 11u;       // float boxes[]: with CullSettings::staticPoints
                                                   // the box of each patch's control points,
                                              // structure of arrays: boxes[c * patchCount + p],
                                              // c = min x, y, z, max x, y, z (kBoxFloats),
                                              // rounded outward (CULL_PATCH_BOXES)
OSD_CULL_CONST uint kCullBindingDeferred = 15u;  // uint deferred[]: the listed-triangle
                                                 // candidates (below)
// (CullMethod::table). The tangent-plane table: per term (target | j << 8 | k << 16 | l << 24,
// floatBitsToUint(weight)). A buffer, not GLSL constants: lavapipe's LLVM backend needs
// 150-190 s to compile the kernel with 516-entry constant arrays, 0.4 s with this buffer.

// counters[]: survivors appended per patch type, then indirect draw counts per type (read by
// vkCmdDrawIndirectCount at byte offset 4 * kCounterDraws*).
OSD_CULL_CONST uint kCounterSurvivorsBezier = 0u;
OSD_CULL_CONST uint kCounterSurvivorsGregory = 1u;
OSD_CULL_CONST uint kCounterDrawsBezier = 2u;
OSD_CULL_CONST uint kCounterDrawsGregory = 3u;
OSD_CULL_CONST uint kCounterCount = 4u;

// A cone of normals (bound::ConeOfNormals rounded to float), four vec4 per patch:
// cones[4p] = (apex.xyz, sin of the half-angle rounded up),
// cones[4p+1] = (axis.xyz, code): code < 0 for a valid cone, else the BackPatchVerdict that
// says why it never culls (NonFinite, NoNormal, WideCone),
// cones[4p+2] = (G, H, max |coordinate|, min |Bu x Bv|) of bound::DerivativeBounds and the
// cone (Bezier patches; min 0 for Gregory), rounded up / down,
// cones[4p+3] = (max radius rounded up, half-angle in radians rounded up, 0, 0): what
// bound::widenCone needs.
// deferred[]: the patches the cull kernel hands to the listed-triangle pass
// (CULL_DRAWN_DEFER, shaders/cull/cull_main.glsl), in two lists: the Bezier candidates from
// word 0, the Gregory ones from word kDeferredHeader + 2 * instances * bezierCount (each type
// has its own listed pass: lavapipe pays for both evaluations in every invocation of a pass
// that can meet either). Each list: [0..2] VkDispatchIndirectCommand of its pass (x: groups,
// at most kDeferredMaxGroups, the least maxComputeWorkGroupCount[0] Vulkan allows; the pass
// loops over the rest), [3] candidates, then (instance, patch) per candidate.
OSD_CULL_CONST uint kDeferredCount = 3u;
OSD_CULL_CONST uint kDeferredHeader = 4u;
OSD_CULL_CONST uint kDeferredMaxGroups = 65535u;

OSD_CULL_CONST uint kConeVec4s = 4u;
OSD_CULL_CONST uint kBoxFloats = 6u;  // floats per patch in boxes[]

OSD_CULL_CONST uint kCullGroupSize = 64u;   // invocations per workgroup, every variant
OSD_CULL_CONST uint kDrawsGroupSize = 64u;  // write_draws.comp

// ---- Result code, one uint per patch --------------------------------------------------
// bits 0-3   stage that culled the patch (kStage*), kStageNone when it survives;
// bits 4-7   frustum code: the plane (bound::FrustumPlane 0..5) that culled, kFrustumInside,
//            kFrustumNonFinite, or kNotRun;
// bits 8-15  back-patch verdict (bound::BackPatchVerdict) or kNotRun;
// bits 16-23 occlusion verdict (defined by the occlusion stage) or kNotRun.
// Stages run cheapest first and stop at the first cull: later fields stay kNotRun.
OSD_CULL_CONST uint kStageNone = 0u;
OSD_CULL_CONST uint kStageFrustum = 1u;
OSD_CULL_CONST uint kStageBackPatch = 2u;
OSD_CULL_CONST uint kStageOcclusion = 3u;

// Back-patch verdicts: the values of bound::BackPatchVerdict (static_assert in
// osd_cull/bound/cull_reference.cpp). For the back-patch and occlusion stages verdict 0
// means "culled"; the frustum field holds the plane that culled (0..5) or a reason to keep.
OSD_CULL_CONST uint kVerdictBackFacing = 0u;
OSD_CULL_CONST uint kVerdictFrontFacing = 1u;
OSD_CULL_CONST uint kVerdictSilhouette = 2u;
OSD_CULL_CONST uint kVerdictEyeOutsideBackRegion = 3u;
OSD_CULL_CONST uint kVerdictNonFinite = 4u;
OSD_CULL_CONST uint kVerdictNoNormal = 5u;
OSD_CULL_CONST uint kVerdictWideCone = 6u;
OSD_CULL_CONST uint kVerdictNoFiniteEye = 7u;
OSD_CULL_CONST uint kVerdictDrawnTriangles = 8u;

OSD_CULL_CONST uint kFrustumInside = 6u;     // bound::kNoPlane: not outside one plane
OSD_CULL_CONST uint kFrustumNonFinite = 7u;  // NaN/Inf point or clip coordinate: kept
OSD_CULL_CONST uint kNotRun = 0xFu;          // in a 4-bit field; 0xFF in an 8-bit field

OSD_CULL_CONST uint kResultShiftFrustum = 4u;
OSD_CULL_CONST uint kResultShiftBackPatch = 8u;
OSD_CULL_CONST uint kResultShiftOcclusion = 16u;
// Every field "not run", stage none: what a patch starts with.
OSD_CULL_CONST uint kResultInitial = 0x00FFFFF0u;

// fp32 margins, each derived in docs/algorithms/cull-kernel.md so that every GPU cull is
// a cull of the double reference (bound/, margin bound::kRelativeMargin = 1e-12):
// - frustum and cone tests: a quantity counts as having a sign only beyond
//   kCullRelativeMargin times an upper bound of the magnitudes it is computed from (their
//   fp32 error, including rounding the inputs to float, is below 15 * 2^-24 of that bound);
// - tangent plane (shaders/cull/tangent_plane_common.glsl): arithmetic error < 35 * 2^-24 ma,
//   input rounding < 4 * 2^-24 mb, and the reference's own margin < 1.32e-11 mr / |e.w|;
//   the factored form (tangent_plane_factored.glsl): arithmetic error < 34 * 2^-24 M, input
//   rounding bounded with 2^-24 (kTpInputMargin uses 16 times that);
// - the fp64 cone kernels (tcone-fp64, ncone-fp64): the cull-region test in double, where
//   only rounding the cone and the eye to float remains (below 4 * 2^-24 of |E| + |l|).
#ifdef __cplusplus
inline constexpr float kCullRelativeMargin = 1e-5f;
inline constexpr float kCullFp64RelativeMargin = 1e-6f;
inline constexpr float kTpArithmeticMargin = 1e-5f;
inline constexpr float kTpInputMargin = 9.5367431640625e-7f;  // 2^-20 = 16 * 2^-24
inline constexpr float kTpReferenceMargin = 2.4e-11f;
#else
const float kCullRelativeMargin = 1e-5;
const float kCullFp64RelativeMargin = 1e-6;
const float kTpArithmeticMargin = 1e-5;
const float kTpInputMargin = 9.5367431640625e-7;
const float kTpReferenceMargin = 2.4e-11;
#endif

struct CullConstants {
  mat4 viewProjection;  // world to clip space
  vec4 eye;             // xyz: eye (world, bound::eyePosition), NaN when the projection has
                        // no finite eye; w: 1 / |e.w| of the homogeneous eye
                        // (bound::homogeneousEye), 0 when there is no finite eye
  vec4 viewport;        // xy: width, height in pixels; z: uniform tessellation level; w: max
                        // level (as DrawConstants.viewport, for the drawn-triangle bound)
  uint patchCount;      // patches [0, bezierCount) are Bezier, the rest Gregory
  uint bezierCount;
  uint pointStride;      // floats between control points
  uint pointOffset;      // float index of control point 0
  uint drawChunkBezier;  // patches per indirect draw (draw_chunks.h batch limits)
  uint drawChunkGregory;
  float tessPixelsPerSegment;  // adaptive tessellation target (DrawConstants.eye.w); 0: the
                               // draws tessellate uniformly (viewport.z)
  float snapPerDistance;       // bound::snapPerDistance of the draws (drawn-triangle bound)
};

// Instances (issue 10): one dispatch culls every instance of a patch set, invocation =
// (instance, patch). Per instance the values of CullConstants that depend on the model
// matrix, composed in double on the host (frame::instanceCamera) and rounded once; the
// kernel reads them in place of CullConstants' (cull_main.glsl). Instance i's outputs:
// results[i * patchCount + p], drawList[i * patchCount + slot], counters[i * kCounterCount +
// k], commands[i * (patchCount + 2) + c]; the displaced view is DisplacedView[i].
struct CullInstance {
  mat4 viewProjection;    // object to clip space (CullConstants.viewProjection)
  vec4 eye;               // CullConstants.eye in object space
  float snapPerDistance;  // CullConstants.snapPerDistance
  // 1: this view's adaptive levels are precomputed (the levels pass, frame::TessLevelsPass):
  // patch p's drawn levels are tessLevels[levelSlot * patchCount + p] (kCullBindingTessLevels),
  // exact, and the draws of this instance read the same entries. The kernel does not branch
  // on it: CullPass composes the drawn-triangle kernel for its level source (CULL_LEVELS).
  uint exactLevels;
  uint levelSlot;  // with exactLevels: the instance's slot of tessLevels[] (of patchCount entries)
  float pad2;
};

// What the displaced bounds (shaders/cull/displaced_bound.glsl) need of a view beyond
// CullConstants.viewProjection: the camera-aligned frustum works in camera space.
struct DisplacedView {
  mat4 view;         // world to camera space (camera looking down -z)
  mat4 projection;   // camera to clip space
  uint perspective;  // 1: bound::isCameraAlignedPerspective(projection), the CAF can be built
  uint pad0;
  uint pad1;
  uint pad2;
};

OSD_CULL_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(osd_cull::shader::CullConstants) == 128);
static_assert(sizeof(osd_cull::shader::CullInstance) == 96);
#endif
#endif
