// The drawn-triangle bound (bound/drawn_triangles.h): the tessellation shape bound against
// the device's real tessellator, and the margins against brute force on drawn triangles.
#include "osd_cull/bound/drawn_triangles.h"

#include "osd_cull/bound/clip_space.h"
#include "osd_cull/bound/cone_of_normals.h"
#include "osd_cull/bound/drawn_triangle_set.h"
#include "osd_cull/bound/patch_eval.h"
#include "osd_cull/bound/tangent_plane.h"
#include "osd_cull/error.h"
#include "support/tessellator_capture.h"
#include "support/vk_test_context.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <string>

namespace osd_cull {
namespace {

using bound::QuadTessLevels;
using bound::TriangleShape;

class DrawnTrianglesTest : public test::VkTest {};

// Level sets: equal levels, random levels with random transition edges, and extremes.
std::vector<QuadTessLevels> levelSweep() {
  std::vector<QuadTessLevels> sets;
  for (double n = 1; n <= 16; ++n) sets.push_back({{n, n, n, n}, {0, 0, 0, 0}});
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> level(1, 32), coin(0, 3);
  for (int i = 0; i < 3000; ++i) {
    QuadTessLevels l;
    for (int e = 0; e < 4; ++e) {
      l.lo[e] = level(rng);
      l.hi[e] = coin(rng) == 0 ? level(rng) : 0.0;
      if (i % 3 == 0) l.lo[e] = 1 + (l.lo[e] - 1) * 2, l.hi[e] = 0.0;  // up to 63
    }
    sets.push_back(l);
  }
  sets.push_back({{1, 1, 1, 32}, {0, 0, 0, 0}});
  sets.push_back({{32, 1, 32, 1}, {0, 0, 0, 0}});
  sets.push_back({{1, 32, 1, 32}, {0, 0, 0, 0}});
  sets.push_back({{1, 1, 1, 1}, {31, 0, 0, 0}});
  sets.push_back({{31, 2, 5, 1}, {1, 0, 7, 0}});
  sets.push_back({{64, 64, 64, 64}, {0, 0, 0, 0}});
  sets.push_back({{2, 3, 2, 3}, {0, 0, 0, 0}});
  return sets;
}

std::string describeLevels(const QuadTessLevels& l) {
  std::string s = "levels lo";
  for (int e = 0; e < 4; ++e) s += (e ? "," : " ") + std::to_string(l.lo[e]);
  s += " hi";
  for (int e = 0; e < 4; ++e) s += (e ? "," : " ") + std::to_string(l.hi[e]);
  return s;
}

TEST_F(DrawnTrianglesTest, ShapeBoundHoldsForTheDevicesTessellator) {
  if (!context().info().optional.geometryShader) GTEST_SKIP() << "no geometry shaders";
  test::TessellatorCapture capture(context());
  double worstPhi = 0.0, worstPsi = 0.0;
  for (const QuadTessLevels& l : levelSweep()) {
    const auto triangles = capture.capture(l);
    ASSERT_FALSE(triangles.empty());
    const TriangleShape bound = bound::triangleShape(l);
    const TriangleShape measured = test::measuredShape(triangles);
    const std::string where = describeLevels(l);
    EXPECT_LE(measured.phi, bound.phi * (1 + 1e-6)) << where;
    EXPECT_LE(measured.psi, bound.psi * (1 + 1e-6)) << where;
    EXPECT_GE(measured.minEdge, bound.minEdge * (1 - 1e-6)) << where;
    if (std::getenv("OSD_CULL_PRINT_SHAPES"))
      std::printf("%s: phi %.4f / %.4f, psi %.5f / %.5f\n", where.c_str(), measured.phi, bound.phi,
                  measured.psi, bound.psi);
    if (triangles.size() > 2) {  // all levels 1 (two triangles) is exact
      worstPhi = std::max(worstPhi, measured.phi / bound.phi);
      worstPsi = std::max(worstPsi, measured.psi / bound.psi);
    }
  }
  std::printf("largest measured / bound: phi %.3f, psi %.3f\n", worstPhi, worstPsi);
}

}  // namespace
}  // namespace osd_cull

namespace osd_cull {
namespace {

// A bumpy bicubic cap over [-s, s]^2 facing +z (N = Bu x Bv points up).
std::array<glm::dvec3, 16> randomCap(std::mt19937& rng, double curvature) {
  std::uniform_real_distribution<double> jitter(-0.08, 0.08);
  std::array<glm::dvec3, 16> b;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const double x = (i - 1.5) / 1.5 + jitter(rng), y = (j - 1.5) / 1.5 + jitter(rng);
      b[4 * j + i] = glm::dvec3(x, y, -curvature * (x * x + y * y) + jitter(rng));
    }
  return b;
}

// A view of a randomCap() from below, some distance away: at a random elevation, or, with
// `silhouette`, just past (by up to `past` radians) the elevation where `culled` stops
// holding.
glm::dmat4 capView(std::mt19937& rng, const std::function<bool(const glm::dmat4&)>& culled,
                   bool silhouette, double past = 2e-3) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(-1.3, -0.05);
  const double dir = 3.14159 * unit(rng), dist = 3.0 + 20.0 * (unit(rng) + 1);
  auto viewAt = [&](double a) {
    const glm::dvec3 eye(dist * std::cos(a) * std::cos(dir), dist * std::cos(a) * std::sin(dir),
                         dist * std::sin(a) - 0.3);
    return glm::perspective(1.2, 1.0, 0.05, 200.0) *
           glm::lookAt(eye, glm::dvec3(0.0), glm::dvec3(0, 0, 1));
  };
  double a = angle(rng);
  if (silhouette) {
    double culledAt = -1.5, keptAt = 0.3;
    for (int it = 0; it < 40; ++it) {
      const double mid = 0.5 * (culledAt + keptAt);
      (culled(viewAt(mid)) ? culledAt : keptAt) = mid;
    }
    a = culledAt - 0.5 * past * (unit(rng) + 1.0);
  }
  return viewAt(a);
}

// capView() at the surface tangent-plane test's limit.
glm::dmat4 capView(std::mt19937& rng, const std::array<glm::dvec3, 16>& b, bool silhouette) {
  return capView(
      rng,
      [&](const glm::dmat4& m) {
        return bound::tangentPlaneTest(b, m, bound::clipSpaceEyeSign(m)).culled;
      },
      silhouette);
}

// Whether a captured triangle (corners in the tessellator's order) faces the eye, corners
// evaluated in double.
bool facesEye(const std::array<glm::dvec3, 16>& b, const test::ParamTriangle& t,
              const glm::dvec3& eye) {
  glm::dvec3 p[3];
  for (int k = 0; k < 3; ++k) p[k] = bound::evaluateBezier(b, t[k].x, t[k].y).position;
  const glm::dvec2 d1 = t[1] - t[0], d2 = t[2] - t[0];
  const double orient = d1.x * d2.y - d1.y * d2.x > 0 ? 1.0 : -1.0;
  return orient * glm::dot(eye - p[0], glm::cross(p[1] - p[0], p[2] - p[0])) > 0.0;
}

// (E - B) . (Bu x Bv) at (u, v) from the 64 tangent-plane coefficients, and directly.
TEST(DrawnTriangles, TangentPlaneCoefficientsAreTheFacingPolynomial) {
  std::mt19937 rng(3);
  const glm::dmat4 vp =
      glm::perspective(1.0, 1.0, 0.1, 100.0) *
      glm::lookAt(glm::dvec3(0.3, -0.2, 6.0), glm::dvec3(0.0), glm::dvec3(0, 1, 0));
  const glm::dvec3 eye = *bound::eyePosition(vp);
  const double sigma = bound::clipSpaceEyeSign(vp);
  const double ew = std::abs(bound::homogeneousEye(vp).w);
  for (int trial = 0; trial < 5; ++trial) {
    const auto b = randomCap(rng, 0.4);
    const auto planes = bound::tangentPlaneControlPlanes(b, vp);
    for (double u : {0.0, 0.3, 0.77, 1.0})
      for (double v : {0.0, 0.5, 0.9}) {
        double poly = 0.0;
        for (int r = 0; r < 8; ++r)
          for (int c = 0; c < 8; ++c)
            poly += bernstein(7, c, u) * bernstein(7, r, v) * sigma * planes.z[8 * r + c] / ew;
        const auto s = bound::evaluateBezier(b, u, v);
        const double direct = glm::dot(eye - s.position, glm::cross(s.du, s.dv));
        EXPECT_NEAR(poly, direct, 1e-9 * (1.0 + std::abs(direct))) << u << " " << v;
      }
  }
}

// Brute force: with the drawn-triangle bound, no triangle of a culled patch faces the eye
// (corners evaluated in double, triangles as the device's tessellator makes them); without
// it, some do (the test can fail).
TEST_F(DrawnTrianglesTest, CulledPatchesHaveNoFrontFacingDrawnTriangle) {
  if (!context().info().optional.geometryShader) GTEST_SKIP() << "no geometry shaders";
  test::TessellatorCapture capture(context());
  const std::vector<QuadTessLevels> levelSets = {
      {{1, 1, 1, 1}, {0, 0, 0, 0}}, {{2, 2, 2, 2}, {0, 0, 0, 0}}, {{4, 4, 4, 4}, {0, 0, 0, 0}},
      {{3, 7, 2, 5}, {0, 0, 0, 0}}, {{2, 4, 2, 4}, {2, 0, 0, 3}}, {{16, 16, 16, 16}, {0, 0, 0, 0}}};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  uint64_t culled[3] = {}, surfaceOnlyViolations = 0;
  for (const QuadTessLevels& levels : levelSets) {
    const auto triangles = capture.capture(levels);
    const TriangleShape shape = bound::triangleShape(levels);
    for (int trial = 0; trial < 300; ++trial) {
      const auto b = randomCap(rng, 0.05 + 0.2 * (unit(rng) + 1.0));
      const glm::dmat4 vp = capView(rng, b, trial % 2 == 1);
      const double sigma = bound::clipSpaceEyeSign(vp);
      const double ew = std::abs(bound::homogeneousEye(vp).w);
      const glm::dvec3 e = *bound::eyePosition(vp);
      bool anyFront = false;
      for (const auto& t : triangles) anyFront = anyFront || facesEye(b, t, e);
      const auto tp = bound::tangentPlaneTest(b, vp, sigma);
      const auto tpDrawn = bound::tangentPlaneTest(
          b, vp, sigma, ew * bound::tangentPlaneDrawnMargin(b, e, shape, 0.0));
      const auto tcone = bound::buildConeFromTangentCones(b);
      const auto ncone = bound::buildConeOfNormals(b);
      const bool tc = bound::testConeOfNormals(tcone, e).culled &&
                      bound::testConeOfNormals(bound::widenCone(tcone, b, e, shape, 0.0), e).culled;
      const bool nc = bound::testConeOfNormals(ncone, e).culled &&
                      bound::testConeOfNormals(bound::widenCone(ncone, b, e, shape, 0.0), e).culled;
      surfaceOnlyViolations += tp.culled && anyFront;
      culled[0] += tpDrawn.culled, culled[1] += tc, culled[2] += nc;
      ASSERT_FALSE(anyFront && (tpDrawn.culled || tc || nc))
          << "trial " << trial << " tp " << tpDrawn.culled << " tcone " << tc << " ncone " << nc;
    }
  }
  std::printf(
      "culled with the bound: tangent plane %llu, TCONE %llu, NCONE %llu of %zu; "
      "surface-only tangent-plane culls with a front-facing triangle: %llu\n",
      (unsigned long long)culled[0], (unsigned long long)culled[1], (unsigned long long)culled[2],
      levelSets.size() * 300, (unsigned long long)surfaceOnlyViolations);
  EXPECT_GT(surfaceOnlyViolations, 0u) << "the views should include silhouette chords";
  EXPECT_GT(culled[0], 30u);
  EXPECT_GT(culled[1], 5u);
  EXPECT_GT(culled[2], 15u);
}

// Level sets the listed test meets: uniform tessellation (equal levels; transition edges
// with n segments on each half), and general integer levels from levelSweep().
std::vector<QuadTessLevels> listedLevelSets() {
  std::vector<QuadTessLevels> sets;
  for (double n = 1; n <= 16; ++n) {
    sets.push_back({{n, n, n, n}, {0, 0, 0, 0}});
    sets.push_back({{n, n, n, n}, {n, 0, 0, 0}});
    sets.push_back({{n, n, n, n}, {0, n, 0, n}});
  }
  sets.push_back({{32, 32, 32, 32}, {32, 32, 0, 0}});
  const auto sweep = levelSweep();
  for (size_t i = 16; i < sweep.size(); i += 10) sets.push_back(sweep[i]);
  return sets;
}

// Each triangle the device's tessellator draws is one forEachDrawnTriangle lists, and each
// of its inner vertices lies within tessCoordError of the listed point (outer ones within
// tessellatorPointError of their edge) (listed points are at
// least 1/64 apart, so the nearest one is the vertex's).
TEST_F(DrawnTrianglesTest, EveryTriangleTheDevicesTessellatorDrawsIsListed) {
  if (!context().info().optional.geometryShader) GTEST_SKIP() << "no geometry shaders";
  test::TessellatorCapture capture(context());
  size_t checked = 0;
  double worstCoord = 0.0;  // largest coordinate error / tessCoordError
  using Cell = std::pair<long, long>;
  using Key = std::pair<long long, long long>;
  auto cellOf = [](glm::dvec2 q) { return Cell{std::lround(q.x * 64.0), std::lround(q.y * 64.0)}; };
  for (const QuadTessLevels& l : listedLevelSets()) {
    std::map<Cell, std::vector<glm::dvec2>> points;
    std::set<std::array<Key, 3>> listed;
    // Exact listed points computed two ways (1 - 1/i, (i - 1)/i) differ in the last bit.
    auto key = [](glm::dvec2 q) {
      return Key{std::llround(q.x * 0x1p30), std::llround(q.y * 0x1p30)};
    };
    bound::forEachDrawnTriangle(l, [&](const bound::DomainTriangle& t, bool) {
      std::array<Key, 3> k{key(t[0]), key(t[1]), key(t[2])};
      for (const glm::dvec2& q : t) {
        auto& bucket = points[cellOf(q)];
        if (std::find(bucket.begin(), bucket.end(), q) == bucket.end()) bucket.push_back(q);
      }
      std::sort(k.begin(), k.end());
      listed.insert(k);
    });
    auto nearest = [&](glm::dvec2 q) {
      glm::dvec2 best(-1.0);
      const Cell c = cellOf(q);
      for (long dx = -1; dx <= 1; ++dx)
        for (long dy = -1; dy <= 1; ++dy) {
          auto it = points.find({c.first + dx, c.second + dy});
          if (it == points.end()) continue;
          for (const glm::dvec2& p : it->second)
            if (glm::length(p - q) < glm::length(best - q)) best = p;
        }
      return best;
    };
    // Inner vertices are drawn at the tessellator's coordinates; outer ones are re-evaluated
    // from round(t n) / n (non-transition edges: not in the capture), so they only need the
    // tessellator's own error.
    const double coordError = bound::tessCoordError(l);
    double outerError = 0.0;
    for (int e = 0; e < 4; ++e)
      outerError = std::max(outerError, bound::tessellatorPointError(l.lo[e] + l.hi[e]));
    outerError += std::ldexp(1.0, -21);
    const std::string where = describeLevels(l);
    for (const auto& t : capture.capture(l)) {
      const glm::dvec2 d1 = t[1] - t[0], d2 = t[2] - t[0];
      if (std::abs(d1.x * d2.y - d1.y * d2.x) < 1e-9) continue;  // draws nothing
      std::array<Key, 3> k;
      for (int c = 0; c < 3; ++c) {
        const glm::dvec2 p = nearest(t[c]);
        const double err = std::max(std::abs(p.x - t[c].x), std::abs(p.y - t[c].y));
        const bool outer = p.x == 0.0 || p.x == 1.0 || p.y == 0.0 || p.y == 1.0;
        ASSERT_LE(err, outer ? outerError : coordError)
            << where << ": vertex (" << t[c].x << "," << t[c].y << ")";
        if (!outer) worstCoord = std::max(worstCoord, err / coordError);
        k[c] = key(p);
      }
      std::sort(k.begin(), k.end());
      ASSERT_TRUE(listed.count(k))
          << where << ": triangle (" << t[0].x << "," << t[0].y << ") (" << t[1].x << "," << t[1].y
          << ") (" << t[2].x << "," << t[2].y << ") is not listed";
      ++checked;
    }
  }
  std::printf("%zu drawn triangles, all listed; largest vertex offset / tessCoordError %.2f\n",
              checked, worstCoord);
  EXPECT_GT(checked, 10000u);
}

TEST(DrawnTriangles, ListingRejectsLevelsItCannotList) {
  EXPECT_THROW(bound::forEachDrawnTriangle({{2.5, 2, 2, 2}, {0, 0, 0, 0}},
                                           [](const bound::DomainTriangle&, bool) {}),
               Error);
  EXPECT_THROW(bound::forEachDrawnTriangle({{0, 2, 2, 2}, {0, 0, 0, 0}},
                                           [](const bound::DomainTriangle&, bool) {}),
               Error);
  EXPECT_THROW(bound::forEachDrawnTriangle({{65, 2, 2, 2}, {0, 0, 0, 0}},
                                           [](const bound::DomainTriangle&, bool) {}),
               Error);
}

// Brute force for the tightened test: a patch whose listed triangles all face away has no
// front-facing drawn triangle. The same check catches a deliberately over-tightened listing
// that leaves out the ring triangles (the test can fail), and the listing culls more than
// the worst-case bound.
TEST_F(DrawnTrianglesTest, ListedTrianglesCullNoPatchWithAFrontFacingTriangle) {
  if (!context().info().optional.geometryShader) GTEST_SKIP() << "no geometry shaders";
  test::TessellatorCapture capture(context());
  const std::vector<QuadTessLevels> levelSets = {
      {{1, 1, 1, 1}, {0, 0, 0, 0}},    {{2, 2, 2, 2}, {0, 0, 0, 0}}, {{4, 4, 4, 4}, {0, 0, 0, 0}},
      {{4, 4, 4, 4}, {4, 0, 0, 0}},    {{3, 7, 2, 5}, {0, 0, 0, 0}}, {{8, 8, 8, 8}, {0, 8, 0, 0}},
      {{16, 16, 16, 16}, {0, 0, 0, 0}}};
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  uint64_t listedCulls = 0, boundCulls = 0, surfaceCulls = 0, achievable = 0, overTightMisses = 0;
  for (const QuadTessLevels& levels : levelSets) {
    const auto triangles = capture.capture(levels);
    const TriangleShape shape = bound::triangleShape(levels);
    for (int trial = 0; trial < 300; ++trial) {
      const auto b = randomCap(rng, 0.05 + 0.2 * (unit(rng) + 1.0));
      const glm::dmat4 vp = capView(rng, b, trial % 4 != 0);
      const double sigma = bound::clipSpaceEyeSign(vp);
      const glm::dvec3 e = *bound::eyePosition(vp);
      bool anyFront = false;
      for (const auto& t : triangles) anyFront = anyFront || facesEye(b, t, e);
      const bool listed = bound::drawnTrianglesFaceAway(b, levels, e, 0.0);
      ASSERT_FALSE(anyFront && listed) << "trial " << trial;
      // Over-tightened: the inner grid only.
      bool innerAway = true;
      bound::forEachDrawnTriangle(levels, [&](const bound::DomainTriangle& t, bool ring) {
        if (ring || !innerAway) return;
        innerAway =
            bound::triangleFacesAway(bound::evaluateBezier(b, t[0].x, t[0].y).position,
                                     bound::evaluateBezier(b, t[1].x, t[1].y).position,
                                     bound::evaluateBezier(b, t[2].x, t[2].y).position, e, 0.0);
      });
      overTightMisses += anyFront && innerAway;
      const bool surface = bound::tangentPlaneTest(b, vp, sigma).culled;
      const double ew = std::abs(bound::homogeneousEye(vp).w);
      surfaceCulls += surface;
      achievable += surface && !anyFront;
      listedCulls += surface && listed;
      boundCulls += bound::tangentPlaneTest(b, vp, sigma,
                                            ew * bound::tangentPlaneDrawnMargin(b, e, shape, 0.0))
                        .culled;
    }
  }
  std::printf(
      "tangent-plane culls: surface %llu (without a front-facing triangle %llu), with the bound "
      "%llu, with the listed triangles %llu; front-facing triangles the inner grid alone "
      "misses: %llu\n",
      (unsigned long long)surfaceCulls, (unsigned long long)achievable,
      (unsigned long long)boundCulls, (unsigned long long)listedCulls,
      (unsigned long long)overTightMisses);
  EXPECT_GT(overTightMisses, 0u) << "the brute force must catch an over-tightened listing";
  EXPECT_GT(listedCulls, boundCulls + boundCulls / 2);
  // Three in four eyes sit within 2e-3 rad past the surface test's limit, inside the
  // margin the listed test needs for the tessellator's fixed-point coordinates on many of
  // them: measured 74% of the surface culls without a front-facing triangle.
  EXPECT_GT(double(listedCulls), 0.65 * double(achievable));
}

// A Gregory patch over randomCap(): the cap's boundary, and each interior point split into
// Fp and Fm moved apart by up to `split` (as at a valence-3 or -5 vertex, where OpenSubdiv
// makes Gregory patches), so that the rational blends matter.
std::array<glm::dvec3, 20> randomGregoryCap(std::mt19937& rng, double curvature, double split) {
  const auto b = randomCap(rng, curvature);
  std::uniform_real_distribution<double> jitter(-split, split);
  std::array<glm::dvec3, 20> g;
  for (size_t k = 0; k < 16; ++k)
    if (bound::kGregoryBoundary[k] >= 0) g[bound::kGregoryBoundary[k]] = b[k];
  for (const auto& in : bound::kGregoryInterior)
    for (int f : {in.a, in.b})
      g[f] = b[4 * in.j + in.i] + glm::dvec3(jitter(rng), jitter(rng), 0.5 * jitter(rng));
  return g;
}

// Whether every listed triangle of the Gregory patch faces away with no margin at all.
bool listedAwayWithoutMargin(const std::array<glm::dvec3, 20>& g, const QuadTessLevels& levels,
                             const glm::dvec3& e) {
  bool away = true;
  bound::forEachDrawnTriangle(levels, [&](const bound::DomainTriangle& t, bool) {
    if (!away) return;
    glm::dvec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = bound::evaluateGregory(g, t[k].x, t[k].y).position;
    away = bound::triangleFacesAway(p[0], p[1], p[2], e, 0.0);
  });
  return away;
}

// G bounds the exact derivatives of the rational Gregory surface (sampled densely, corners
// included), and the listing rejects a patch of the wrong size.
TEST(DrawnTriangles, GregoryDerivativeBoundHoldsForTheRationalSurface) {
  std::mt19937 rng(5);
  double worst = 0.0;
  for (int trial = 0; trial < 50; ++trial) {
    const auto g = randomGregoryCap(rng, 0.3, 0.4);
    const double bound = bound::gregoryDerivativeBound(g);
    for (int i = 0; i <= 40; ++i)
      for (int j = 0; j <= 40; ++j) {
        const auto s = bound::evaluateGregory(g, i / 40.0, j / 40.0);
        const double d = std::max(glm::length(s.du), glm::length(s.dv));
        ASSERT_LE(d, bound) << "trial " << trial << " at " << i << "," << j;
        worst = std::max(worst, d / bound);
      }
  }
  std::printf("largest |dS/du|, |dS/dv| / gregoryDerivativeBound: %.3f\n", worst);
  EXPECT_GT(worst, 0.3);  // the bound is not vacuous
  const std::array<glm::dvec3, 19> wrong{};
  EXPECT_THROW(
      bound::drawnTrianglesFaceAway(wrong, {{2, 2, 2, 2}, {0, 0, 0, 0}}, glm::dvec3(0, 0, -5), 0.0),
      Error);
}

// Brute force for Gregory patches: no patch the listed test culls has a front-facing
// triangle (the device's triangles, the rational surface evaluated in double at the
// device's coordinates), over many views just past the limit of the listing without its
// margin; without the margin, some culled patches do have one (the test can fail).
TEST_F(DrawnTrianglesTest, ListedGregoryTrianglesCullNoPatchWithAFrontFacingTriangle) {
  if (!context().info().optional.geometryShader) GTEST_SKIP() << "no geometry shaders";
  test::TessellatorCapture capture(context());
  // Levels that are not powers of two give the tessellator's coordinates a rounding error.
  const std::vector<QuadTessLevels> levelSets = {
      {{1, 1, 1, 1}, {0, 0, 0, 0}},     {{2, 2, 2, 2}, {0, 0, 0, 0}},
      {{5, 5, 5, 5}, {0, 0, 0, 0}},     {{6, 6, 6, 6}, {0, 6, 0, 0}},
      {{8, 8, 8, 8}, {8, 0, 0, 8}},     {{3, 7, 2, 5}, {0, 0, 0, 0}},
      {{12, 12, 12, 12}, {0, 0, 0, 0}}, {{16, 16, 16, 16}, {0, 0, 0, 0}}};
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  uint64_t listedCulls = 0, achievable = 0, noMarginMisses = 0, views = 0;
  for (const QuadTessLevels& levels : levelSets) {
    const auto triangles = capture.capture(levels);
    for (int trial = 0; trial < 200; ++trial) {
      const auto g = randomGregoryCap(rng, 0.05 + 0.4 * unit(rng), 0.3 * unit(rng));
      // A quarter of the views within 1e-6 rad past the unmargined listing's limit, where
      // only the margin separates the listing from the drawn triangles; half within 2e-3.
      const bool edge = trial % 4 == 1;
      const glm::dmat4 vp = capView(
          rng,
          [&](const glm::dmat4& m) {
            return listedAwayWithoutMargin(g, levels, *bound::eyePosition(m));
          },
          trial % 4 != 0, edge ? 1e-6 : 2e-3);
      const glm::dvec3 e = *bound::eyePosition(vp);
      bool anyFront = false;
      for (const auto& t : triangles) {
        glm::dvec3 p[3];
        for (int k = 0; k < 3; ++k) p[k] = bound::evaluateGregory(g, t[k].x, t[k].y).position;
        const glm::dvec2 d1 = t[1] - t[0], d2 = t[2] - t[0];
        const double orient = d1.x * d2.y - d1.y * d2.x > 0 ? 1.0 : -1.0;
        anyFront =
            anyFront || orient * glm::dot(e - p[0], glm::cross(p[1] - p[0], p[2] - p[0])) > 0;
      }
      const bool listed = bound::drawnTrianglesFaceAway(g, levels, e, 0.0);
      ASSERT_FALSE(anyFront && listed) << describeLevels(levels) << " trial " << trial;
      const bool noMargin = listedAwayWithoutMargin(g, levels, e);
      noMarginMisses += anyFront && noMargin;
      // The share kept is counted away from the edge views (which no margin can cull).
      achievable += !edge && noMargin && !anyFront;
      listedCulls += !edge && listed;
      ++views;
    }
  }
  std::printf(
      "Gregory: %llu views; away from the limit, listed culls %llu of %llu without a "
      "front-facing triangle; "
      "front-facing triangles the listing without margin misses: %llu\n",
      (unsigned long long)views, (unsigned long long)listedCulls, (unsigned long long)achievable,
      (unsigned long long)noMarginMisses);
  EXPECT_GT(noMarginMisses, 0u) << "the brute force must catch the listing without its margin";
  EXPECT_GT(double(listedCulls), 0.4 * double(achievable));
}

}  // namespace
}  // namespace osd_cull
