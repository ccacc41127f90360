#include "support/vk_test_eval.h"

#include <array>

namespace osd_cull::test {

namespace {

std::array<double, 4> bernstein(double t) {
  const double s = 1.0 - t;
  return {s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t};
}

}  // namespace

glm::dvec3 evalBezier(std::span<const glm::dvec3> cp, double u, double v) {
  const auto bu = bernstein(u), bv = bernstein(v);
  glm::dvec3 p(0.0);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) p += bu[i] * bv[j] * cp[4 * j + i];
  return p;
}

glm::dvec3 evalGregory(std::span<const glm::dvec3> g, double u, double v) {
  // Corner c's points: P = g[5c], Ep = g[5c+1], Em = g[5c+2], Fp = g[5c+3], Fm = g[5c+4];
  // Ep points along the edge to corner c+1, Em along the edge to corner c-1 (corners
  // (0,0), (1,0), (1,1), (0,1)). Fp lies next to Ep's edge, Fm next to Em's.
  auto blend = [](const glm::dvec3& fp, const glm::dvec3& fm, double wp, double wm) {
    const double sum = wp + wm;
    return sum <= 0.0 ? 0.5 * (fp + fm) : (wp * fp + wm * fm) / sum;
  };
  const double su = 1.0 - u, sv = 1.0 - v;
  std::array<glm::dvec3, 16> b{};
  auto at = [&](int i, int j) -> glm::dvec3& { return b[4 * j + i]; };
  at(0, 0) = g[0];
  at(1, 0) = g[1];
  at(0, 1) = g[2];
  at(3, 0) = g[5];
  at(3, 1) = g[6];
  at(2, 0) = g[7];
  at(3, 3) = g[10];
  at(2, 3) = g[11];
  at(3, 2) = g[12];
  at(0, 3) = g[15];
  at(0, 2) = g[16];
  at(1, 3) = g[17];
  // Each Fp lies next to its corner's Ep edge and takes over as the point approaches
  // that edge (weight -> 1), Fm likewise for the Em edge:
  at(1, 1) = blend(g[3], g[4], u, v);      // corner 0: Ep edge v = 0, Em edge u = 0
  at(2, 1) = blend(g[8], g[9], v, su);     // corner 1: Ep edge u = 1, Em edge v = 0
  at(2, 2) = blend(g[13], g[14], su, sv);  // corner 2: Ep edge v = 1, Em edge u = 1
  at(1, 2) = blend(g[18], g[19], sv, u);   // corner 3: Ep edge u = 0, Em edge v = 1
  return evalBezier(b, u, v);
}

glm::dvec3 evalPatch(const PatchSet& set, uint32_t patch, double u, double v) {
  const auto cp = set.controlPoints(patch);
  return set.type(patch) == PatchType::Bezier ? evalBezier(cp, u, v) : evalGregory(cp, u, v);
}

}  // namespace osd_cull::test
