// The one way shaders read control points (GpuPatchSet::points(), PatchSet order): the
// draw stages (shaders/patch/patch_common.glsl) and the cull kernel
// (shaders/cull/cull_common.glsl) both call controlPoint(i).
//
// The includer defines POINTS_BINDING (in set 0) and declares push constants `pc` with
// pointStride and pointOffset (DrawConstants, CullConstants): control point i is floats
// [pc.pointOffset + i * pc.pointStride, +3). The variant define OSD_CULL_POINTS_BDA (set by
// the host from the device's bufferDeviceAddress feature) chooses where the floats are:
// - 1: the binding holds a PointSource (shared/point_source.h) with the device address of
//   float 0, and points are read through GL_EXT_buffer_reference. The address arithmetic is
//   64-bit, so the point buffer may be larger than maxStorageBufferRange (128 MiB on
//   lavapipe: 524,288 Bezier patches) and 4 GiB alike;
// - 0: the binding holds the floats themselves, at most maxStorageBufferRange bytes (the
//   host checks and names the limit before anything is recorded).
#ifndef OSD_CULL_CONTROL_POINTS_GLSL
#define OSD_CULL_CONTROL_POINTS_GLSL

#if !defined(POINTS_BINDING) || !defined(OSD_CULL_POINTS_BDA)
#error "define POINTS_BINDING and OSD_CULL_POINTS_BDA before including control_points.glsl"
#endif

#if OSD_CULL_POINTS_BDA
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include <shared/point_source.h>

layout(std430, set = 0, binding = POINTS_BINDING) readonly buffer PointSourceBlock {
  PointSource pointSource;
};
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer PointFloats {
  float x;
  float y;
  float z;
};

vec3 controlPoint(uint index) {
  // Byte offset of the point in 64 bits: (offset + index * stride) * 4.
  uint hi, lo, carry;
  umulExtended(pc.pointOffset + index * pc.pointStride, 4u, hi, lo);
  uint addressLo = uaddCarry(pointSource.addressLo, lo, carry);
  PointFloats p = PointFloats(uvec2(addressLo, pointSource.addressHi + hi + carry));
  return vec3(p.x, p.y, p.z);
}
#else
layout(std430, set = 0, binding = POINTS_BINDING) readonly buffer Points { float points[]; };

vec3 controlPoint(uint index) {
  uint base = pc.pointOffset + index * pc.pointStride;
  return vec3(points[base], points[base + 1u], points[base + 2u]);
}
#endif
#endif
