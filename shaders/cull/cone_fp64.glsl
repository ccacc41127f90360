// Back-patch stage of the tcone-fp64 and ncone-fp64 methods: cone.glsl with the cone's
// cull-region test in double (Loop, Niessner, Eisenacher, section 2; cone_of_normals.glsl),
// the fp64 point of the accuracy-versus-time study (docs/results/accuracy-vs-time.md). The
// cones and the drawn-triangle widening are as in the fp32 kernel. Needs shaderFloat64.
#define CONE_FP64 1
#include "cone_of_normals.glsl"

uint backPatchVerdict(uint patchIndex, uint lane, uint slot, bool run) {
  return run ? coneVerdict(patchIndex) : 0xFFu;
}
