// Push constants and bindings of the bounds pass (shaders/bounds/*, osd_cull/frame/cull/
// bounds_pass), shared by C++ and GLSL. Its output is the cull data the back-patch methods
// or the displaced kernels read (cull_layout.h kCullBindingCones, kConeVec4s vec4 per patch).
#ifndef OSD_CULL_SHARED_BOUNDS_LAYOUT_H
#define OSD_CULL_SHARED_BOUNDS_LAYOUT_H
#include "glsl_compat.h"

OSD_CULL_SHARED_BEGIN

OSD_CULL_CONST uint kBoundsBindingPoints = 0u;  // GpuPatchSet::pointBinding(): control_points.glsl
OSD_CULL_CONST uint kBoundsBindingCones = 1u;   // vec4 cones[]: the cull data written
OSD_CULL_CONST uint kBoundsBindingRanges = 2u;  // vec2 ranges[]: (Dmin, Dmax) per patch,
                                                // read by the displaced output only
OSD_CULL_CONST uint kMaxVectors = 64u;  // vectors one cone is built from, at most (shared memory)

OSD_CULL_CONST uint kBoundsGroupSize = 16u;  // shared memory: 16 x (64 + 20) x 16 bytes

// Which cone a Bezier patch gets (Gregory patches get the Gregory TCONE but with
// kBoundsNoCone).
OSD_CULL_CONST uint kBoundsTCone = 0u;
OSD_CULL_CONST uint kBoundsNCone = 1u;
OSD_CULL_CONST uint kBoundsTangentPlane = 2u;  // Bezier: no cone (the kernel reads the points)
OSD_CULL_CONST uint kBoundsNoCone = 3u;        // no patch gets a cone (displaced Full)

// What the pass writes per patch.
OSD_CULL_CONST uint kBoundsOutputBackPatch = 0u;  // the back-patch cull data (PatchCone layout)
OSD_CULL_CONST uint kBoundsOutputDisplaced = 1u;  // the displaced kernels' data: (Dmin, Dmax,
                                                  // cos a, sin a), (axis, 1 with a cone, else 0)

struct BoundsConstants {
  uint patchCount;  // patches [0, bezierCount) are Bezier, the rest Gregory
  uint bezierCount;
  uint pointStride;  // floats between control points
  uint pointOffset;  // float index of control point 0
  uint method;       // kBoundsTCone, kBoundsNCone, kBoundsTangentPlane or kBoundsNoCone
  float pointError;  // bound of |device coordinate - double reference coordinate| of every
                     // control point (docs/algorithms/bounds-pass.md)
  float shrink;      // 0; tests only: bounds made tighter by this much (must then fail)
  uint outputKind;   // kBoundsOutputBackPatch or kBoundsOutputDisplaced
};

OSD_CULL_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(osd_cull::shader::BoundsConstants) == 32);
#endif
#endif
