#version 450
// One level of the Hi-Z pyramid (Niessner & Loop §4.1): each texel takes the farthest
// (largest) depth of the 2x2 texels of the level below, or of the depth image for the top
// level. Sizes are powers of two (shared/hiz_layout.h), so every reduction is exactly 2x2
// and no source texel is skipped (a 5x5 level reduced to 2x2 would drop a row and a column).
//
// HIZ_SAMPLER: one textureLod() with a VK_SAMPLER_REDUCTION_MODE_MAX linear sampler with
// unnormalized coordinates, placed on the corner shared by the four texels, returns their
// maximum (the texels with non-zero weight). The depth image is sampled with
// CLAMP_TO_BORDER and an opaque white border, so texels past its edge read 1 (far);
// pyramid levels clamp to the edge (only a level one texel wide or high reads past it, and
// its texel covers the whole axis). HIZ_GATHER (the top level from a depth image that has
// no min/max filtering): one textureGather() at the shared corner with a nearest sampler
// and the same white border. Otherwise: four texelFetch() and max().
#include <shared/hiz_layout.h>

layout(local_size_x = 8, local_size_y = 8) in;

layout(push_constant) uniform Push { HiZReduceConstants pc; };
layout(set = 0, binding = 0) uniform sampler2D src;
layout(set = 0, binding = 1, r32f) uniform writeonly image2D dst;

float fetch(ivec2 p) {
  if (pc.srcBounded != 0u && (p.x >= int(pc.srcWidth) || p.y >= int(pc.srcHeight)))
    return kHiZFar;
  p = min(p, ivec2(pc.srcWidth, pc.srcHeight) - 1);
  return texelFetch(src, p, 0).r;
}

void main() {
  ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (t.x >= int(pc.dstWidth) || t.y >= int(pc.dstHeight)) return;
  float depth;
  if (pc.mode == kHiZCopy) {
    depth = fetch(t);
  } else {
#if defined(HIZ_SAMPLER)
    depth = textureLod(src, vec2(2 * t + 1), 0.0).r;
#elif defined(HIZ_GATHER)
    const vec4 g = textureGather(src, vec2(2 * t + 1) / vec2(pc.srcWidth, pc.srcHeight));
    depth = max(max(g.x, g.y), max(g.z, g.w));
#else
    ivec2 s = 2 * t;
    depth = max(max(fetch(s), fetch(s + ivec2(1, 0))), max(fetch(s + ivec2(0, 1)), fetch(s + 1)));
#endif
  }
  imageStore(dst, t, vec4(depth));
}
