// Back-patch stage "tangent-plane": the parametric tangent-plane test with one thread per
// patch (Loop, Niessner, Eisenacher §4.2, DVis with the Pcnt rule of §7), its 64
// coefficients computed by the factored form of tangent_plane_factored.glsl instead of the
// 516 cross4() terms of §5 (docs/algorithms/cull-kernel.md, "The factored form"). fp32
// mirror of bound::tangentPlaneTest through bound::tangentPlaneFactored. Gregory patches:
// the Gregory TCONE (cone_of_normals.glsl).
#include "tangent_plane_factored.glsl"

uint backPatchVerdict(uint patchIndex, uint lane, uint slot, bool run) {
  if (!run) return 0xFFu;
  return isBezier(patchIndex) ? tangentPlaneFactoredVerdict(patchIndex) : coneVerdict(patchIndex);
}
