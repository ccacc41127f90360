// Back-patch stage "tangent-plane": the parametric tangent-plane test with one thread per
// patch, the serial algorithm of Loop, Niessner, Eisenacher section 5 over the table in the
// serial order (cull_layout.h kCullBindingTable), coefficients e . t_i evaluated in world
// space with eye-relative differences (tangent_plane_common.glsl says why). fp32 mirror of
// bound::tangentPlaneTest. Gregory patches: the Gregory TCONE (cone_of_normals.glsl).
//
// Terms whose points are equal (collapsed edges) are exactly zero and skipped, so the
// coefficients along a collapsed edge are exactly 0 with bounds 0 and the Pcnt rule
// classifies the patch as the reference does.
#include "tangent_plane_common.glsl"

uint tangentPlaneVerdict(uint patchIndex) {
  uint first = firstPoint(patchIndex);
  TangentPlanePoint p[16];
  bool finite = matrixIsFinite();
  for (uint k = 0u; k < 16u; ++k) {
    vec3 b = controlPoint(first + k);
    finite = finite && isFiniteF(b);
    p[k] = tangentPlanePoint(b);
  }
  if (!finite) return kVerdictNonFinite;
  if (pc.eye.w == 0.0) return kVerdictNoFiniteEye;
  if (!isFiniteF(pc.eye.xyz)) return kVerdictNonFinite;
  // The serial table is sorted by target: sum one coefficient at a time and count its
  // signs when the target changes (no indexed array of 64 sums).
  const float drawnMargin = tangentPlaneDrawnMargin(patchIndex);
  uvec4 counts = uvec4(0u);
  vec4 sums = vec4(0.0);
  uint target = 0u;
  for (uint k = 0u; k < kTangentPlaneTermCount; ++k) {
    uvec4 t = tangentPlaneTerm(k);
    if (t.x != target) {
      counts += tangentPlaneCounts(sums, drawnMargin);
      sums = vec4(0.0);
      target = t.x;
    }
    if (p[t.y].b == p[t.z].b || p[t.z].b == p[t.w].b || p[t.y].b == p[t.w].b) continue;
    addTangentPlaneTerm(sums, tangentPlaneWeight(k), p[t.y], p[t.z], p[t.w]);
  }
  counts += tangentPlaneCounts(sums, drawnMargin);
  return classifyTangentPlane(counts.z == 0u, counts.x, counts.y, counts.w);
}

uint backPatchVerdict(uint patchIndex, uint lane, uint slot, bool run) {
  if (!run) return 0xFFu;
  return isBezier(patchIndex) ? tangentPlaneVerdict(patchIndex) : coneVerdict(patchIndex);
}
