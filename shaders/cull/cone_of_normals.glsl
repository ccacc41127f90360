// The cone-of-normals back-patch test: fp32 mirror of bound::testConeOfNormals (Loop,
// Niessner, Eisenacher, section 2: TCONE after Sederberg and Meyers, NCONE after Shirman
// and Abi-Ezzi). Cones are built once per static mesh on the host in double and uploaded
// (CullPass): Bezier patches carry the method's TCONE or NCONE, Gregory patches the Gregory
// TCONE (bound::buildGregoryConeFromTangentCones) for every back-patch method.
//
// Culled iff the eye E is in the cone's cull region, dot(a, E - l) + sin(g) |E - l| < 0,
// with a margin of kCullRelativeMargin (|E| + |l|) toward "visible": the fp32 error of the
// left side, including rounding a, l, sin(g) and E to float, is below 15 * 2^-24 (|E| + |l|).
#ifndef OSD_CULL_CULL_CONE_OF_NORMALS_GLSL
#define OSD_CULL_CULL_CONE_OF_NORMALS_GLSL
#include "cull_common.glsl"

uint coneVerdict(uint patchIndex) {
  vec4 apexSin = cones[kConeVec4s * patchIndex];
  vec4 axisCode = cones[kConeVec4s * patchIndex + 1u];
  if (!(axisCode.w < 0.0)) return uint(axisCode.w);  // invalid cone: its reason
  if (pc.eye.w == 0.0) return kVerdictNoFiniteEye;
  vec3 e = pc.eye.xyz;
  if (!isFiniteF(e) || !isFiniteF(apexSin) || !isFiniteF(axisCode.xyz)) return kVerdictNonFinite;
  vec3 d = e - apexSin.xyz;
  float lhs = dot(axisCode.xyz, d) + apexSin.w * length(d);
  float margin = kCullRelativeMargin * (length(e) + length(apexSin.xyz));
  if (!isFiniteF(lhs) || !isFiniteF(margin)) return kVerdictNonFinite;
  return lhs < -margin ? kVerdictBackFacing : kVerdictEyeOutsideBackRegion;
}
#endif
