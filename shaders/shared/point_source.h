// Where the patch draw and cull shaders find the control points when they read them through
// a buffer device address (shaders/common/control_points.glsl), shared by C++
// (osd_cull/frame/draw/gpu_patch_set) and GLSL.
#ifndef OSD_CULL_SHARED_POINT_SOURCE_H
#define OSD_CULL_SHARED_POINT_SOURCE_H
#include "glsl_compat.h"

OSD_CULL_SHARED_BEGIN

// The record at the points binding (draw set binding kBindingPoints, cull set binding
// kCullBindingPoints) of a device address variant: the VkDeviceAddress of float 0 of the
// points buffer, split in two 32-bit halves (GL_EXT_buffer_reference_uvec2). The floats are
// then read as in the plain variant: control point i at [pointOffset + i * pointStride, +3).
struct PointSource {
  uint addressLo;
  uint addressHi;
  uint pad0;
  uint pad1;
};

OSD_CULL_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(osd_cull::shader::PointSource) == 16);
#endif
#endif
