// Push constants of shaders/osd/eval_stencils.comp, shared by C++ (osd_cull/osd) and GLSL
// so that the two cannot drift. Offsets, strides and lengths are those of
// Osd::BufferDescriptor, in floats.
#ifndef OSD_CULL_OSD_EVAL_STENCILS_LAYOUT_H
#define OSD_CULL_OSD_EVAL_STENCILS_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
namespace osd_cull::osd::gpu {
using int32 = std::int32_t;
#else
#define int32 int
#endif

struct EvalStencilsPush {
  int32 srcOffset;  // float index of element 0 of source vertex 0
  int32 srcStride;  // floats from one source vertex to the next
  int32 dstOffset;
  int32 dstStride;
  int32 duOffset;   // derivative outputs (OSD_DERIVATIVES variant only)
  int32 duStride;
  int32 dvOffset;
  int32 dvStride;
  int32 duLength;   // 0: du is not written
  int32 dvLength;   // 0: dv is not written
  int32 start;      // first stencil of this dispatch
  int32 end;        // one past the last stencil
};

#ifdef __cplusplus
static_assert(sizeof(EvalStencilsPush) == 48, "push constants are 12 ints");
}  // namespace osd_cull::osd::gpu
#else
#undef int32
#endif

#endif
