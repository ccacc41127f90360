// Back-patch stage "tangent-plane": the parametric tangent-plane test with one thread per
// patch, the serial algorithm of Loop, Niessner, Eisenacher section 5 over the table in the
// serial order (cull_layout.h kCullBindingTable), in clip space, z components only (section
// 4.1). fp32 mirror of bound::tangentPlaneTest. Gregory patches: the Gregory TCONE (cone_of_normals.glsl).
//
// Rounding: each control plane z_i comes with a bound m_i of the magnitudes summed into it;
// a plane counts as possibly positive unless sigma z_i + kCullRelativeMargin m_i <= 0. Terms
// whose world-space points are equal (collapsed edges) are exactly zero and are skipped, so
// their planes stay exactly 0 with bound 0 and Pcnt classifies the patch as the reference.
#include "tangent_plane_common.glsl"

uint tangentPlaneVerdict(uint patchIndex) {
  uint first = firstPoint(patchIndex);
  vec3 p[16];
  vec4 c[16], m[16];
  bool finite = matrixIsFinite();
  for (uint k = 0u; k < 16u; ++k) {
    p[k] = controlPoint(first + k);
    c[k] = clipPoint(p[k]);
    m[k] = absClipPoint(p[k]);
    finite = finite && isFiniteF(p[k]);
  }
  if (!finite) return kVerdictNonFinite;
  if (pc.eye.w == 0.0) return kVerdictNoFiniteEye;
  float z[64], bound[64];
  for (uint i = 0u; i < 64u; ++i) z[i] = bound[i] = 0.0;
  for (uint k = 0u; k < kTangentPlaneTermCount; ++k) {
    uvec4 t = tangentPlaneTerm(k);
    if (p[t.y] == p[t.z] || p[t.z] == p[t.w] || p[t.y] == p[t.w]) continue;
    float w = tangentPlaneWeight(k);
    z[t.x] += w * cross4Z(c[t.y], c[t.z], c[t.w]);
    bound[t.x] += abs(w) * cross4ZBound(m[t.y], m[t.z], m[t.w]);
  }
  uvec2 counts = uvec2(0u);
  for (uint i = 0u; i < 64u; ++i) {
    finite = finite && isFiniteF(z[i]) && isFiniteF(bound[i]);
    counts += planeSignCounts(z[i], bound[i]);
  }
  return classifyTangentPlane(finite, counts.x, counts.y);
}

uint backPatchVerdict(uint patchIndex, uint lane, uint slot, bool run) {
  if (!run) return 0xFFu;
  return isBezier(patchIndex) ? tangentPlaneVerdict(patchIndex) : coneVerdict(patchIndex);
}
