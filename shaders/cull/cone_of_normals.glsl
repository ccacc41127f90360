// The cone-of-normals back-patch test: fp32 mirror of bound::testConeOfNormals (Loop,
// Niessner, Eisenacher, section 2: TCONE after Sederberg and Meyers, NCONE after Shirman
// and Abi-Ezzi). Cones are built once per static mesh on the host in double and uploaded
// (CullPass), or per moved frame by the bounds pass (shaders/bounds/, DynamicPatchMesh): Bezier patches carry the method's TCONE or NCONE, Gregory patches the Gregory
// TCONE (bound::buildGregoryConeFromTangentCones) for every back-patch method.
//
// Culled iff the eye E is in the cone's cull region, dot(a, E - l) + sin(g) |E - l| < 0,
// with a margin of kCullRelativeMargin (|E| + |l|) toward "visible": the fp32 error of the
// left side, including rounding a, l, sin(g) and E to float, is below 15 * 2^-24 (|E| + |l|).
#ifndef OSD_CULL_CULL_CONE_OF_NORMALS_GLSL
#define OSD_CULL_CULL_CONE_OF_NORMALS_GLSL
#include "cull_common.glsl"
#if CULL_DRAWN
#include "drawn_triangles.glsl"
#endif

// The cull-region test of a cone (apex, axis, sin of the half-angle). With CONE_FP64 (the
// tcone-fp64 and ncone-fp64 kernels, shaderFloat64) it is evaluated in double, and the
// margin only covers rounding the cone and the eye to float (kCullFp64RelativeMargin).
uint coneRegionVerdict(vec3 apex, vec3 axis, float sinAngle) {
#if CONE_FP64
  dvec3 de = dvec3(pc.eye.xyz), dd = de - dvec3(apex);
  double dlhs = dot(dvec3(axis), dd) + double(sinAngle) * length(dd);
  double dmargin = double(kCullFp64RelativeMargin) * (length(de) + length(dvec3(apex)));
  if (!isFiniteF(float(dlhs)) || !isFiniteF(float(dmargin))) return kVerdictNonFinite;
  return dlhs < -dmargin ? kVerdictBackFacing : kVerdictEyeOutsideBackRegion;
#else
  vec3 e = pc.eye.xyz;
  vec3 d = e - apex;
  float lhs = dot(axis, d) + sinAngle * length(d);
  float margin = kCullRelativeMargin * (length(e) + length(apex));
  if (!isFiniteF(lhs) || !isFiniteF(margin)) return kVerdictNonFinite;
  return lhs < -margin ? kVerdictBackFacing : kVerdictEyeOutsideBackRegion;
#endif
}

#if CULL_DRAWN
// bound::widenCone: the cone grows by the angle the drawn triangles' normals can deviate
// from the surface normals, asin(deviation / min |N|), and its apex moves back by
// maxRadius (tan γ' - tan γ) + dv (1 + tan γ'), with tan γ' - tan γ = sin Δ / (cos γ' cos γ).
uint drawnConeVerdict(uint patchIndex, vec4 apexSin, vec3 axis) {
  if (!isBezier(patchIndex)) return kVerdictDrawnTriangles;
  vec4 bounds = cones[kConeVec4s * patchIndex + 2u];  // G, H, max |coordinate|, min |N|
  vec4 shape4 = cones[kConeVec4s * patchIndex + 3u];  // max radius, half-angle
#if CULL_PATCH_BOXES
  // An upper bound of max |E - b| from the box (its farthest corner), as conservative as
  // the distance itself (a larger R widens the cone), without the 16 point loads.
  vec3 c, e;
  patchBox(patchIndex, c, e);
  float dv = drawnVertexError(bounds.z, length(abs(pc.eye.xyz - c) + e) * kDrawnSafety);
#else
  float dv = drawnVertexError(bounds.z, drawnMaxDistance(firstPoint(patchIndex)));
#endif
  float deviation = drawnNormalDeviation(bounds.x, bounds.y, drawnShape(patchIndex), dv);
  if (!(bounds.w > deviation) || !isFiniteF(deviation)) return kVerdictDrawnTriangles;
  float widen = asin(min(1.0, deviation / bounds.w * kDrawnSafety)) * kDrawnSafety + 1e-5;
  float gamma = shape4.y + widen;
  if (!(gamma < 1.5)) return kVerdictDrawnTriangles;
  float tanGamma = tan(gamma) * kDrawnSafety;
  float back = shape4.x * sin(widen) / (cos(gamma) * cos(shape4.y)) * kDrawnSafety +
               dv * (1.0 + tanGamma);
  float sinGamma = min(1.0, sin(gamma) * kDrawnSafety);
  uint v = coneRegionVerdict(apexSin.xyz - back * axis, axis, sinGamma);
  return v == kVerdictBackFacing ? v : kVerdictDrawnTriangles;
}
#endif

uint coneVerdict(uint patchIndex) {
  vec4 apexSin = cones[kConeVec4s * patchIndex];
  vec4 axisCode = cones[kConeVec4s * patchIndex + 1u];
  if (!(axisCode.w < 0.0)) return uint(axisCode.w);  // invalid cone: its reason
  if (pc.eye.w == 0.0) return kVerdictNoFiniteEye;
  if (!isFiniteF(pc.eye.xyz) || !isFiniteF(apexSin) || !isFiniteF(axisCode.xyz))
    return kVerdictNonFinite;
  uint v = coneRegionVerdict(apexSin.xyz, axisCode.xyz, apexSin.w);
#if CULL_DRAWN
  if (v == kVerdictBackFacing) v = drawnConeVerdict(patchIndex, apexSin, axisCode.xyz);
#endif
  return v;
}
#endif
