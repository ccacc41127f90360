#include "osd_cull/bound/clip_space.h"

#include <glm/matrix.hpp>

#include <cmath>

namespace osd_cull::bound {

glm::dvec4 clipPoint(const glm::dvec3& p, const glm::dmat4& viewProj) {
  return viewProj * glm::dvec4(p, 1.0);
}

glm::dvec4 absClipPoint(const glm::dvec3& p, const glm::dmat4& viewProj) {
  glm::dmat4 a;
  for (int c = 0; c < 4; ++c) a[c] = glm::abs(viewProj[c]);
  return a * glm::dvec4(glm::abs(p), 1.0);
}

bool allFinite(std::span<const glm::dvec3> points) {
  for (const glm::dvec3& p : points)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  return true;
}

bool allFinite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

namespace {

// det [[a0 b0 c0], [a1 b1 c1], [a2 b2 c2]]
double det3(double a0, double a1, double a2, double b0, double b1, double b2, double c0, double c1,
            double c2) {
  return a0 * (b1 * c2 - b2 * c1) - b0 * (a1 * c2 - a2 * c1) + c0 * (a1 * b2 - a2 * b1);
}

}  // namespace

// Appendix A of Loop, Nießner, Eisenacher: x = det(y,z,w rows), y = -det(x,z,w),
// z = det(x,y,w), w = -det(x,y,z), each over the columns a, b, c.
glm::dvec4 cross4(const glm::dvec4& a, const glm::dvec4& b, const glm::dvec4& c) {
  return {det3(a.y, a.z, a.w, b.y, b.z, b.w, c.y, c.z, c.w),
          -det3(a.x, a.z, a.w, b.x, b.z, b.w, c.x, c.z, c.w),
          det3(a.x, a.y, a.w, b.x, b.y, b.w, c.x, c.y, c.w),
          -det3(a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z)};
}

double cross4Z(const glm::dvec4& a, const glm::dvec4& b, const glm::dvec4& c) {
  return det3(a.x, a.y, a.w, b.x, b.y, b.w, c.x, c.y, c.w);
}

double cross4ZBound(const glm::dvec4& a, const glm::dvec4& b, const glm::dvec4& c) {
  const glm::dvec4 p = glm::abs(a), q = glm::abs(b), r = glm::abs(c);
  return p.x * (q.y * r.w + q.w * r.y) + q.x * (p.y * r.w + p.w * r.y) +
         r.x * (p.y * q.w + p.w * q.y);
}

// adj(M) * (0,0,1,0) is the third column of the adjugate: entry r is the cofactor C(2, r)
// of M (row z of M removed). Then M * e = det(M) * (0,0,1,0), so e is the point with clip
// x = y = w = 0, for any invertible M (perspective: the camera centre, scaled).
glm::dvec4 homogeneousEye(const glm::dmat4& viewProj) {
  // Rows x, y, w of M (GLM stores columns: M[col][row]).
  auto m = [&](int row, int col) { return viewProj[col][row]; };
  const int rows[3] = {0, 1, 3};
  glm::dvec4 e;
  for (int r = 0; r < 4; ++r) {
    // Minor without row 2 (z) and column r; cofactor sign (-1)^(2 + r); adj = cofactor^T.
    int cols[3];
    int n = 0;
    for (int c = 0; c < 4; ++c)
      if (c != r) cols[n++] = c;
    const double minor = det3(m(rows[0], cols[0]), m(rows[1], cols[0]), m(rows[2], cols[0]),
                              m(rows[0], cols[1]), m(rows[1], cols[1]), m(rows[2], cols[1]),
                              m(rows[0], cols[2]), m(rows[1], cols[2]), m(rows[2], cols[2]));
    e[r] = (r % 2 == 0) ? minor : -minor;
  }
  return e;
}

std::optional<glm::dvec3> eyePosition(const glm::dmat4& viewProj) {
  if (clipSpaceEyeSign(viewProj) == 0.0) return std::nullopt;
  const glm::dvec4 e = homogeneousEye(viewProj);
  return glm::dvec3(e) / e.w;
}

double clipSpaceEyeSign(const glm::dmat4& viewProj) {
  if (!allFinite(viewProj)) return 0.0;
  const glm::dvec4 e = homogeneousEye(viewProj);
  // Bound of the products summed in e.w (the x, y, w rows and columns x, y, z of M).
  auto m = [&](int row, int col) { return std::abs(viewProj[col][row]); };
  const double bound = m(0, 0) * (m(1, 1) * m(3, 2) + m(3, 1) * m(1, 2)) +
                       m(0, 1) * (m(1, 0) * m(3, 2) + m(3, 0) * m(1, 2)) +
                       m(0, 2) * (m(1, 0) * m(3, 1) + m(3, 0) * m(1, 1));
  if (!std::isfinite(e.w) || !(std::abs(e.w) > kRelativeMargin * bound)) return 0.0;
  // Derivation (Loop et al. §4.1 in column-vector form): cross4(Ma, Mb, Mc) =
  // det(M) M^-T cross4(a, b, c), so with clip eye f = M e = det(M) (0,0,1,0):
  // T'_z = f·T' / det(M) = e·T. For world points a = (B, 1), b = (Bu, 0), c = (Bv, 0) and
  // e = e.w (E, 1): e·cross4(a, b, c) = det[e; a; b; c] = e.w · dot(Bu x Bv, E - B).
  return e.w > 0.0 ? 1.0 : -1.0;
}

}  // namespace osd_cull::bound
