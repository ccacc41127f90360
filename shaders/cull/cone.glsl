// Back-patch stage of the tcone and ncone methods: the cone test of cone_of_normals.glsl,
// one thread per patch. Which cone a Bezier patch carries (TCONE or NCONE) is decided on
// the host (frame/cull_method_cones.cpp); the kernel is the same.
#include "cone_of_normals.glsl"

uint backPatchVerdict(uint patchIndex, uint lane, uint slot, bool run) {
  return run ? coneVerdict(patchIndex) : 0xFFu;
}
