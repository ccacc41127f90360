// Stencil evaluation for osd_cull::osd::VkComputeEvaluator, the Vulkan counterpart of
// OpenSubdiv's glslComputeKernel.glsl (EvalStencils): for stencil i in [start, end)
//   dst[i] = sum over its entries j of weights[j] * src[indices[j]]
// with vertices located by Osd::BufferDescriptor offsets and strides (push constants)
// and kLength floats per vertex (specialization constant, one pipeline per length).
// Defining OSD_DERIVATIVES adds du and dv outputs weighted by duWeights and dvWeights
// (limit stencils). src and dst may be the same buffer, as in Osd::Mesh, where refined
// vertices follow the control vertices they are computed from: no buffer is `restrict`.
#version 450
#include "eval_stencils_layout.h"

layout(local_size_x = 64) in;
layout(constant_id = 0) const int kLength = 3;

layout(push_constant) uniform PushBlock { EvalStencilsPush pc; };

layout(std430, binding = 0) readonly buffer SrcBuffer { float srcData[]; };
layout(std430, binding = 1) writeonly buffer DstBuffer { float dstData[]; };
layout(std430, binding = 2) readonly buffer SizesBuffer { int sizes[]; };
layout(std430, binding = 3) readonly buffer OffsetsBuffer { int offsets[]; };
layout(std430, binding = 4) readonly buffer IndicesBuffer { int indices[]; };
layout(std430, binding = 5) readonly buffer WeightsBuffer { float weights[]; };
#ifdef OSD_DERIVATIVES
layout(std430, binding = 6) writeonly buffer DuBuffer { float duData[]; };
layout(std430, binding = 7) writeonly buffer DvBuffer { float dvData[]; };
layout(std430, binding = 8) readonly buffer DuWeightsBuffer { float duWeights[]; };
layout(std430, binding = 9) readonly buffer DvWeightsBuffer { float dvWeights[]; };
#endif

void main() {
  const int stencil = pc.start + int(gl_GlobalInvocationID.x);
  if (stencil >= pc.end) return;
  const int first = offsets[stencil];
  const int count = sizes[stencil];

  float sum[kLength];
  for (int k = 0; k < kLength; ++k) sum[k] = 0.0;
#ifdef OSD_DERIVATIVES
  float du[kLength];
  float dv[kLength];
  for (int k = 0; k < kLength; ++k) du[k] = dv[k] = 0.0;
#endif
  for (int j = first; j < first + count; ++j) {
    const int base = pc.srcOffset + indices[j] * pc.srcStride;
    const float w = weights[j];
#ifdef OSD_DERIVATIVES
    const float wu = duWeights[j];
    const float wv = dvWeights[j];
#endif
    for (int k = 0; k < kLength; ++k) {
      const float x = srcData[base + k];
      sum[k] += w * x;
#ifdef OSD_DERIVATIVES
      du[k] += wu * x;
      dv[k] += wv * x;
#endif
    }
  }

  const int dstBase = pc.dstOffset + stencil * pc.dstStride;
  for (int k = 0; k < kLength; ++k) dstData[dstBase + k] = sum[k];
#ifdef OSD_DERIVATIVES
  if (pc.duLength > 0)
    for (int k = 0; k < kLength; ++k) duData[pc.duOffset + stencil * pc.duStride + k] = du[k];
  if (pc.dvLength > 0)
    for (int k = 0; k < kLength; ++k) dvData[pc.dvOffset + stencil * pc.dvStride + k] = dv[k];
#endif
}
