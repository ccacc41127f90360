#include "osd_cull/bound/tangent_plane_factored.h"

#include "osd_cull/error.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <string>

namespace osd_cull::bound {
namespace {

constexpr double kC2[3] = {1, 2, 1};
constexpr double kC3[4] = {1, 3, 3, 1};
constexpr double kC7[8] = {1, 7, 21, 35, 35, 21, 7, 1};

double l1(const glm::dvec3& v) { return std::abs(v.x) + std::abs(v.y) + std::abs(v.z); }
double maxAbs(const glm::dvec3& v) {
  return std::max(std::abs(v.x), std::max(std::abs(v.y), std::abs(v.z)));
}

}  // namespace

double tangentPlaneFactoredScale(int p, int q) { return kC7[p] * kC7[q] / 9.0; }

TangentPlaneFactored tangentPlaneFactored(std::span<const glm::dvec3> bezier,
                                          const glm::dvec3& eye) {
  if (bezier.size() != 16)
    throw Error(std::string(__FILE__) + ":" + std::to_string(__LINE__) +
                ": a bicubic Bézier patch has 16 control points, got " +
                std::to_string(bezier.size()));
  auto b = [&](int i, int j) { return bezier[static_cast<size_t>(4 * j + i)]; };
  // N' = Γ × Δ in the scaled (5,5) Bernstein basis: N'_ab = C(5,a) C(5,b) N_ab.
  glm::dvec3 n[6][6] = {};
  double nBound[6][6] = {};
  for (int i1 = 0; i1 < 3; ++i1)
    for (int j1 = 0; j1 < 4; ++j1) {
      const glm::dvec3 gamma = b(i1 + 1, j1) - b(i1, j1);
      for (int i2 = 0; i2 < 4; ++i2)
        for (int j2 = 0; j2 < 3; ++j2) {
          const glm::dvec3 delta = b(i2, j2 + 1) - b(i2, j2);
          const double w = kC2[i1] * kC3[i2] * kC3[j1] * kC2[j2];
          n[i1 + i2][j1 + j2] += w * glm::cross(gamma, delta);
          nBound[i1 + i2][j1 + j2] += w * l1(gamma) * l1(delta);
        }
    }
  // G' = (E - A) · N' in the scaled (7,8) basis: G'_pq = C(7,p) C(8,q) G_pq.
  double g[8][9] = {}, gBound[8][9] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) {
      const glm::dvec3 q = eye - b(i, j);
      const double w = kC2[i] * kC3[j];
      for (int a = 0; a < 6; ++a)
        for (int c = 0; c < 6; ++c) {
          g[i + a][j + c] += w * glm::dot(q, n[a][c]);
          gBound[i + a][j + c] += w * maxAbs(q) * nBound[a][c];
        }
    }
  // v-degree 8 -> 7: in the scaled basis degree elevation reads G'_q = d_{q-1} + d_q, so
  // d follows by subtraction from both ends (the middle of the row is never more than four
  // terms away from an end).
  TangentPlaneFactored f;
  auto same = [&](int i0, int j0, int di, int dj) {
    for (int k = 1; k < 4; ++k)
      if (b(i0 + k * di, j0 + k * dj) != b(i0, j0)) return false;
    return true;
  };
  const bool rowV0 = same(0, 0, 1, 0), rowV1 = same(0, 3, 1, 0);
  const bool colU0 = same(0, 0, 0, 1), colU1 = same(3, 0, 0, 1);
  for (int p = 0; p < 8; ++p) {
    double d[8], m[8];
    d[0] = g[p][0];
    m[0] = gBound[p][0];
    for (int q = 1; q < 4; ++q) {
      d[q] = g[p][q] - d[q - 1];
      m[q] = gBound[p][q] + m[q - 1];
    }
    d[7] = g[p][8];
    m[7] = gBound[p][8];
    for (int q = 6; q >= 4; --q) {
      d[q] = g[p][q + 1] - d[q + 1];
      m[q] = gBound[p][q + 1] + m[q + 1];
    }
    for (int q = 0; q < 8; ++q) {
      f.d[static_cast<size_t>(8 * q + p)] = d[q];
      f.bound[static_cast<size_t>(8 * q + p)] = m[q];
      f.collapsed[static_cast<size_t>(8 * q + p)] =
          (q == 0 && rowV0) || (q == 7 && rowV1) || (p == 0 && colU0) || (p == 7 && colU1);
    }
  }
  return f;
}

}  // namespace osd_cull::bound
