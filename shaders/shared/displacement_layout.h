// Descriptor set 1 of displaced patch draws (shaders/patch/displace.glsl,
// osd_cull/frame/draw/gpu_displacement), shared by C++ and GLSL.
#ifndef OSD_CULL_SHARED_DISPLACEMENT_LAYOUT_H
#define OSD_CULL_SHARED_DISPLACEMENT_LAYOUT_H
#include "glsl_compat.h"

OSD_CULL_SHARED_BEGIN

OSD_CULL_CONST uint kDisplaceSet = 1u;
OSD_CULL_CONST uint kDisplaceBindingMap = 0u;     // sampler2D: R32_SFLOAT map, mips 0..maxLod
OSD_CULL_CONST uint kDisplaceBindingUVs = 1u;     // vec4 patchUVs[2 * patch]: texture
                                                  // coordinates of corners (0,0), (1,0) and
                                                  // (1,1), (0,1), bilinear over the patch
OSD_CULL_CONST uint kDisplaceBindingParams = 2u;  // DisplacementParams
OSD_CULL_CONST uint kDisplaceBindingEdges = 3u;   // vec4 edgeDisplacement[3 * patch]: the
                                                  // displacement's variation along each edge
                                                  // (world units, gl_TessLevelOuter order):
                                                  // whole edge, first half, second half
                                                  // (frame::EdgeDisplacement; patch.tesc)
OSD_CULL_CONST uint kDisplaceBindingRanges = 4u;  // vec2 ranges[patch]: (Dmin, Dmax) of the
                                                  // patch, rounded outward as the cull
                                                  // kernel's (packDisplacementRanges); the
                                                  // depth clamp of patch.tesc

struct DisplacementParams {
  vec4 map;   // x: scale, y: midlevel, z: level of detail sampled, w: 1 / width (texels)
  vec4 size;  // x: 1 / height, y: max |D| of the map, zw: unused
};

OSD_CULL_SHARED_END

#endif
