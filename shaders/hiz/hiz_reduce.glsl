// The 2 x 2 step of the Hi-Z pyramid shared by the builds that reduce several levels in one
// dispatch (hiz_blocks.comp, hiz_single_pass.comp). Level sizes are max(1, level0 >> l)
// (shared/hiz_layout.h): once a level is one texel wide (or high), the texel above it has
// one source column (row), and the values computed for the missing one are left out.
#ifndef OSD_CULL_HIZ_REDUCE_GLSL
#define OSD_CULL_HIZ_REDUCE_GLSL
#include <shared/hiz_layout.h>

ivec2 hizLevelSize(uvec2 level0, uint l) { return ivec2(max(uvec2(1u), level0 >> l)); }

// The farthest of the (up to) four values below texel t of level l + 1 that lie inside
// level l, of size `size`; v[dy][dx] is the value of source 2t + (dx, dy).
float hizReduce(ivec2 size, ivec2 t, float v00, float v10, float v01, float v11) {
  const bool x1 = 2 * t.x + 1 < size.x, y1 = 2 * t.y + 1 < size.y;
  float m = v00;
  if (x1) m = max(m, v10);
  if (y1) m = max(m, v01);
  if (x1 && y1) m = max(m, v11);
  return m;
}
#endif
