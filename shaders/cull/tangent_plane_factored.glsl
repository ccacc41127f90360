// The 64 world-space coefficients of the parametric tangent-plane test by the factored form
// (docs/algorithms/cull-kernel.md, "The factored form"; double mirror
// bound::tangentPlaneFactored, which the tests compare with the §5 table):
//
//   F(u,v) ∝ det(E - B, Bu, Bv) = 9 (E - A) · (Γ × Δ)
//
// A = the first three columns of control points (the u de Casteljau split B = (1-u)A + uC),
// Γ = C - A the u-differences (bidegree (2,3)), Δ the v-differences (bidegree (3,2)).
// N' = Γ × Δ: 144 cross products into a (5,5) polynomial; G' = (E - A) · N': 432 dot
// products into a (7,8) polynomial whose v-degree is exactly 7 (§3); with integer
// (scaled-Bernstein) weights the reduction to 8 x 8 is d_q = G'_q - d_{q-1} from both ends.
// The scaled coefficient d_pq is F_i C(7,p) C(7,q) / 9 (i = 8q + p): same sign.
//
// The code is generated straight-line (frame::tangentPlaneFactoredGlsl(), as the macro
// TANGENT_PLANE_FACTORED_SIGNS): every index is a constant and there are no local arrays,
// which lavapipe compiles in seconds (loops over local arrays: 40-190 s unrolled, and rolled
// the dynamic indexing costs what the table did; cull-kernel.md has the figures).
//
// Rounding (cull-kernel.md derives it): a coefficient counts as "may be positive" unless
//   d + kTpArithmeticMargin M + input + reference <= 0,
// M = Σ w |E - a|_∞ |Γ|_1 |Δ|_1 through the same weights (|·| in the reduction) bounds the
// fp32 error (< 34 u M); input = kTpInputMargin g Σ w (|Γ|_1|Δ|_1 + 6 |E - a|~ Z) bounds the
// effect of rounding the double points and eye to float (g >= |E| + |b|, Z counts the
// differences that are not exactly zero); reference = kTpReferenceMargin W C^3 / |e.w|
// scaled, the reference's own margin. A bound is 0 only where every product has a zero
// difference, and then the coefficient is exactly 0. Along a boundary of four equal points
// (the teapot's poles) the reference skips every term too and does not count the
// coefficient (Pcnt, §7); any other zero-bound coefficient gets the smallest positive
// margin, so it counts as possibly positive and negative as the reference counts it
// (bound::TangentPlaneFactored::collapsed says why).
#ifndef OSD_CULL_CULL_TANGENT_PLANE_FACTORED_GLSL
#define OSD_CULL_CULL_TANGENT_PLANE_FACTORED_GLSL
#include "tangent_plane_common.glsl"

const float kTpC7[8] = float[](1.0, 7.0, 21.0, 35.0, 35.0, 21.0, 7.0, 1.0);
const float kTpSmallestMargin = 1.17549435e-38;  // smallest normal float

bool allEqual(vec3 a, vec3 b, vec3 c, vec3 d) { return a == b && b == c && c == d; }

// Sign counts of one scaled coefficient d_pq with its arithmetic and input margin m (see the
// file comment): (may be positive, may be negative, not finite, may be above -drawn).
uvec4 tangentPlaneFactoredCount(float d, float m, int p, int q, float reference, float drawn,
                                bool collapsed) {
  const float scale = kTpC7[p] * kTpC7[q] / 9.0;
  const float margin = m > 0.0 ? m + reference * scale : collapsed ? 0.0 : kTpSmallestMargin;
  return uvec4(d + margin > 0.0 ? 1u : 0u, d - margin < 0.0 ? 1u : 0u,
               isFiniteF(d) && isFiniteF(margin) ? 0u : 1u,
               d + margin + drawn * scale > 0.0 ? 1u : 0u);
}

// uvec4 tangentPlaneFactoredSigns(vec3 b[16], float inputError, float reference, float drawn,
// bvec4 collapsed): generated straight-line code (frame::tangentPlaneFactoredGlsl()).
TANGENT_PLANE_FACTORED_SIGNS

uint tangentPlaneFactoredVerdict(uint patchIndex) {
  const uint first = firstPoint(patchIndex);
  vec3 b[16];
  bool finite = matrixIsFinite();
  float bMax = 0.0, c = 0.0;
  for (uint k = 0u; k < 16u; ++k) {
    b[k] = controlPoint(first + k);
    finite = finite && isFiniteF(b[k]);
    bMax = max(bMax, maxAbs(b[k]));
    c = max(c, clipMagnitude(b[k]));
  }
  if (!finite) return kVerdictNonFinite;
  if (pc.eye.w == 0.0) return kVerdictNoFiniteEye;
  if (!isFiniteF(pc.eye.xyz)) return kVerdictNonFinite;
  const float inputError = kTpInputMargin * (maxAbs(pc.eye.xyz) + bMax);
  const float reference = kTpReferenceMargin * kTangentPlaneWeightBound * c * c * c * pc.eye.w;
  const bvec4 collapsed =
      bvec4(allEqual(b[0], b[1], b[2], b[3]), allEqual(b[12], b[13], b[14], b[15]),
            allEqual(b[0], b[4], b[8], b[12]), allEqual(b[3], b[7], b[11], b[15]));
  const uvec4 counts = tangentPlaneFactoredSigns(b, inputError, reference,
                                                 tangentPlaneDrawnMargin(patchIndex, b), collapsed);
  return classifyTangentPlane(counts.z == 0u, counts.x, counts.y, counts.w);
}
#endif
