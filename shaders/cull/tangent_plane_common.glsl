// Shared parts of the parametric tangent-plane test (Loop, Niessner, Eisenacher, "Effective
// Back-Patch Culling for Hardware Tessellation"): the 64 coefficients e . t_i of section 4.2
// accumulated from the table of section 5, with their rounding bounds, and the DVis
// classification with the Pcnt rule of section 7. fp32 mirror of bound/tangent_plane.h.
//
// Why world space and not clip space: section 4.1 evaluates e . t_i as the z component of
// the clip-space planes (f = [0 0 a 0]) to save work; the classification itself "does not
// depend on a coordinate system". In fp32 the clip-space form loses the sign to
// cancellation: cross4Z of three clip points of a small patch is (patch size / distance)^2
// smaller than the products it is summed from, about 1e-4 on BigGuy at level 2, close to
// fp32 resolution. We evaluate the same coefficients in world space with the eye E:
//   e . cross4(b_j, b_k, b_l) = -e.w det3(b_j - E, b_k - b_j, b_l - b_j),
// and with sigma = sign(e.w) (bound::clipSpaceEyeSign)
//   sigma t'_z,i = |e.w| F_i,   F_i = sum w (E - b_j) . ((b_k - b_j) x (b_l - b_j)),
// so F_i > 0 is "may be front-facing" exactly as sigma t'_z,i > 0 in the reference. The
// differences b_k - b_j are as small as the patch, so rounding is relative to the patch.
//
// Rounding (docs/algorithms/cull-kernel.md): F_i is kept as "may be positive" unless
//   F_i + kTpArithmeticMargin ma_i + kTpInputMargin mb_i + kTpReferenceMargin mr_i / |e.w| <= 0
// with ma_i = sum |w| |E - b_j|_1 |d_k|_1 |d_l|_1 (bounds every product, fp32 arithmetic
// error < 35 u ma_i), mb_i = sum |w| g (|d_k|_1 |d_l|_1 + 2 |E - b_j|_1 (|d_k|_1 + |d_l|_1))
// with g >= |E| + |b| on the term's points (rounding the double points and eye to float
// moves F_i by < 4 u mb_i), and mr_i = sum |w| C^3 with C >= every clip magnitude of the
// term's points (6 mr_i / |e.w| bounds the reference's own margin base m_i / |e.w|), so
// every GPU cull is a cull of the double reference. u = 2^-24.
#ifndef OSD_CULL_CULL_TANGENT_PLANE_COMMON_GLSL
#define OSD_CULL_CULL_TANGENT_PLANE_COMMON_GLSL
#include "cone_of_normals.glsl"

// Term k of the table: (target, j, k, l) and the weight.
uvec4 tangentPlaneTerm(uint k) {
  uint v = table[k].x;
  return uvec4(v & 0xFFu, (v >> 8u) & 0xFFu, (v >> 16u) & 0xFFu, v >> 24u);
}
float tangentPlaneWeight(uint k) { return uintBitsToFloat(table[k].y); }

float l1(vec3 v) { return abs(v.x) + abs(v.y) + abs(v.z); }
float maxAbs(vec3 v) { return max(abs(v.x), max(abs(v.y), abs(v.z))); }

// Largest clip-space magnitude |viewProj|_r (|b|, 1) over the rows x, y, w (the ones
// cross4Z reads): bound::absClipPoint's components.
float clipMagnitude(vec3 b) {
  vec4 m = absClipPoint(b);
  return max(m.x, max(m.y, m.w));
}

// What each term needs of a control point: q = E - b and (|q|_1, max |b_c|, clipMagnitude).
struct TangentPlanePoint {
  vec3 b;
  vec3 q;
  vec3 mags;
};

TangentPlanePoint tangentPlanePoint(vec3 b) {
  TangentPlanePoint p;
  p.b = b;
  p.q = pc.eye.xyz - b;
  p.mags = vec3(l1(p.q), maxAbs(b), clipMagnitude(b));
  return p;
}

// Running sums of one coefficient: F, ma, mb, mr (see the file comment).
void addTangentPlaneTerm(inout vec4 sums, float w, TangentPlanePoint pj, TangentPlanePoint pk,
                         TangentPlanePoint pl) {
  vec3 dk = pk.b - pj.b, dl = pl.b - pj.b;
  float ek = l1(dk), el = l1(dl), aw = abs(w);
  float g = maxAbs(pc.eye.xyz) + max(pj.mags.y, max(pk.mags.y, pl.mags.y));
  float c = max(pj.mags.z, max(pk.mags.z, pl.mags.z));
  sums += vec4(w * dot(pj.q, cross(dk, dl)), aw * pj.mags.x * ek * el,
               aw * g * (ek * el + 2.0 * pj.mags.x * (ek + el)), aw * c * c * c);
}

// Sign counts of one coefficient from its sums: (may be positive, may be negative, not
// finite, may be above -drawnMargin). drawnMargin is tangentPlaneDrawnMargin() (0 when the
// kernel respects the surface only).
uvec4 tangentPlaneCounts(vec4 sums, float drawnMargin) {
  float margin = kTpArithmeticMargin * sums.y + kTpInputMargin * sums.z +
                 kTpReferenceMargin * sums.w * pc.eye.w;
  bool finite = isFiniteF(sums) && isFiniteF(margin);
  return uvec4(sums.x + margin > 0.0 ? 1u : 0u, sums.x - margin < 0.0 ? 1u : 0u,
               finite ? 0u : 1u, sums.x + margin + drawnMargin > 0.0 ? 1u : 0u);
}

// Section 4.2 DVis with section 7's Pcnt rule from the counts over all 64 coefficients;
// pcntDrawn counts the coefficients above -drawnMargin (a patch culled by the surface test
// that only the drawn triangles keep gets kVerdictDrawnTriangles).
uint classifyTangentPlane(bool finite, uint pcnt, uint ncnt, uint pcntDrawn) {
  if (!finite) return kVerdictNonFinite;
  if (pcnt == 0u) return pcntDrawn == 0u ? kVerdictBackFacing : kVerdictDrawnTriangles;
  if (ncnt == 0u) return kVerdictFrontFacing;
  return kVerdictSilhouette;
}

// tangentPlaneDrawnMargin() of bound/drawn_triangles.h for the Bezier patch with net b, in
// the units of the world-space coefficients: (R + dv) deviation + dv G^2, R = max |E - b|.
float tangentPlaneDrawnMargin(uint patchIndex, vec3 b[16]) {
#if CULL_DRAWN
  vec3 d = drawnDerivativeBounds(b);
  float r = drawnMaxDistance(b);
  float dv = drawnVertexError(d.z, r);
  float mu = (r + dv) * drawnNormalDeviation(d.x, d.y, drawnShape(patchIndex), dv) +
             dv * d.x * d.x;
  return isFiniteF(mu) ? mu * kDrawnSafety : 3.0e38;
#else
  return 0.0;
#endif
}

// The same, loading the net (on lavapipe each load is a loop over the SIMD lanes: a caller
// that has the points passes them).
float tangentPlaneDrawnMargin(uint patchIndex) {
#if CULL_DRAWN
  vec3 b[16];
  uint first = firstPoint(patchIndex);
  for (uint k = 0u; k < 16u; ++k) b[k] = controlPoint(first + k);
  return tangentPlaneDrawnMargin(patchIndex, b);
#else
  return 0.0;
#endif
}
#endif
