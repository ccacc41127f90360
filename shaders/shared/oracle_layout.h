// Push constants and buffers of the item-buffer count (shaders/oracle/count_items.comp),
// shared by C++ (osd_cull/frame/visibility_oracle) and GLSL.
#ifndef OSD_CULL_SHARED_ORACLE_LAYOUT_H
#define OSD_CULL_SHARED_ORACLE_LAYOUT_H
#include "glsl_compat.h"

OSD_CULL_SHARED_BEGIN

// counts[] holds one counter per patch, then these three:
OSD_CULL_CONST uint kCountBackground = 0u;  // at counts[patchCount + 0]
OSD_CULL_CONST uint kCountOccluder = 1u;    // at counts[patchCount + 1]
OSD_CULL_CONST uint kCountUnknown = 2u;     // at counts[patchCount + 2]: values > patchCount
OSD_CULL_CONST uint kCountExtra = 3u;

OSD_CULL_CONST uint kCountGroupSize = 8u;  // 8 x 8 pixels per workgroup

struct CountConstants {
  uint width;       // image size in pixels
  uint height;
  uint patchCount;  // item values 1..patchCount are patches 0..patchCount-1
  uint tileLog2;    // the screen is split into 2^t x 2^t tiles
  uint tileWidth;   // ceil(width / 2^t)
  uint tileHeight;  // ceil(height / 2^t)
  uint pad0;
  uint pad1;
};

OSD_CULL_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(osd_cull::shader::CountConstants) == 32);
#endif
#endif
