// The Gregory TCONE of a 20-point Gregory-basis patch (bound::buildGregoryConeFromTangent-
// Cones and its gregoryTangentCone): the tangent G_u is a non-negative combination of the
// differences of the Bezier-net candidates plus the signed Fp - Fm differences of the
// rational blends' derivatives. The index tables (kGregoryDu, kGregoryDv: pairs (hi, lo) meaning P[hi] - P[lo];
// kGregoryRu, kGregoryRv: (a, b, sign)) are generated on the host from the same tables the
// reference uses (osd_cull/patch/patch_eval.h), see BoundsPass.
#ifndef OSD_CULL_BOUNDS_GREGORY_GLSL
#define OSD_CULL_BOUNDS_GREGORY_GLSL
#include "bounds_common.glsl"

void addGregoryDifference(uint first, int hi, int lo, float sign) {
  vec3 v = sign * (pointAt(uint(hi)) - pointAt(uint(lo)));
  addVector(v, differenceError(v));
}

// One direction's tangent cone, the narrower of the reference's two constructions:
// (B) the cone of every d_k (candidate differences) and r_m (signed Fp - Fm directions);
// (A) G_u / 3 lies in conv{d_k} + ball(ρ), ρ = Σ |r_m| / 9, so with h the smallest part of
//     a d_k along the main cone's axis and P the largest part across it, G_u is within
//     the angle of tangent (P + ρ) / (h - ρ) of the axis when h > ρ. All rounded outward.
DirCone gregoryTangentCone(uint first, bool alongU) {
  uint dCount = alongU ? kGregoryDuCount : kGregoryDvCount;
  uint rCount = alongU ? kGregoryRuCount : kGregoryRvCount;
  gCount = 0u;
  [[dont_unroll]] for (uint i = 0u; i < dCount; ++i) {
    ivec2 d = alongU ? kGregoryDu[i] : kGregoryDv[i];
    addGregoryDifference(first, d.x, d.y, 1.0);
  }
  [[dont_unroll]] for (uint i = 0u; i < rCount; ++i) {
    ivec3 r = alongU ? kGregoryRu[i] : kGregoryRv[i];
    addGregoryDifference(first, r.x, r.y, float(r.z));
  }
  DirCone all = boundDirections();
  float rho = 0.0;
  [[dont_unroll]] for (uint i = dCount; i < gCount; ++i) rho += length(vecAt(i)) + errAt(i);
  rho = rho / 9.0 * (1.0 + 16.0 * kU);
  gCount = dCount;  // (A): the main cone of the d_k alone
  DirCone main = boundDirections();
  if (!main.valid) return all;
  float h = 3.0e38, perp = 0.0;
  [[dont_unroll]] for (uint k = 0u; k < gCount; ++k) {
    vec3 v = vecAt(k);
    float e = (errAt(k) + 8.0 * kU * length(v)) * 1.01;
    float along = dot(v, main.axis);
    h = min(h, along - e);
    perp = max(perp, length(v - along * main.axis) + e);
  }
  h *= 1.0 - 8.0 * kU;
  perp *= 1.0 + 8.0 * kU;
  if (!(h > rho)) return all;
  float across = (perp + rho) * (1.0 + 2.0 * kU), ahead = (h - rho) * (1.0 - 2.0 * kU);
  float s = across / sqrt(across * across + ahead * ahead) * (1.0 + 8.0 * kU);
  if (all.valid && !(s < all.sinAngle)) return all;
  return coneFromSine(main.axis, s);
}

DirCone gregoryCone(uint first) {
  DirCone cu = gregoryTangentCone(first, true);
  DirCone cv = gregoryTangentCone(first, false);
  return combineTangentCones(cu, cv);
}
#endif
