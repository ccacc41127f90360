// Displacement-aware adaptive tessellation (docs/algorithms/displacement.md,
// "Tessellation"): the map's variation along an edge (DisplacementMap::variationAlong), the
// levels both sides of a shared edge compute (frame::patchTessLevels, the double mirror of
// shaders/patch/tess_levels.glsl), and the draw: a closed displaced mesh whose map is
// continuous across every edge shows no crack, a deliberately mismatched level does.
#include "adapters/load_mesh.h"
#include "osd_cull/bound/displaced_map.h"
#include "osd_cull/frame/camera.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/draw/gpu_patch_set.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/frame/draw/tess_levels.h"
#include "osd_cull/frame/verify/crack_count.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "support/temp_dir.h"
#include "support/test_data.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

namespace osd_cull {
namespace {

using frame::DisplacedTessellation;

bound::DisplacementMap procedural(double scale, uint32_t maxLod = 0) {
  return {"procedural", 64, 64, scene::proceduralDisplacementTexels(64, 4), scale, 0.5, maxLod};
}

// Total variation of map.sample() at the map's maxLod along a -> b, densely sampled.
double sampledVariation(const bound::DisplacementMap& map, glm::dvec2 a, glm::dvec2 b, int n) {
  double total = 0.0, previous = map.sample(a, map.maxLod());
  for (int i = 1; i <= n; ++i) {
    const double v = map.sample(a + (b - a) * (double(i) / n), map.maxLod());
    total += std::abs(v - previous);
    previous = v;
  }
  return std::abs(map.scale()) * total;
}

TEST(DisplacedTessellation, VariationAlongIsTheSampledVariationAndSymmetric) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uv(-1.3, 2.1), len(-0.2, 0.2);
  for (uint32_t lod : {0u, 2u}) {
    const auto map = procedural(-0.75, lod);  // a negative scale: variation is |scale| * ...
    for (int i = 0; i < 200; ++i) {
      const glm::dvec2 a(uv(rng), uv(rng));
      const glm::dvec2 b = i % 5 == 0 ? glm::dvec2(a.x, a.y + len(rng))  // axis-aligned
                                      : a + glm::dvec2(len(rng), len(rng));
      const double v = map.variationAlong(a, b);
      EXPECT_EQ(v, map.variationAlong(b, a)) << "not symmetric";
      // Dense sampling can only find less (it skips extrema between samples), and at 20,000
      // samples over at most ~26 texel cells it finds nearly all of it.
      const double sampled = sampledVariation(map, a, b, 20000);
      EXPECT_GE(v, sampled * (1.0 - 1e-9)) << "lod " << lod << " segment " << i;
      EXPECT_LE(v, sampled * 1.01 + 1e-9) << "lod " << lod << " segment " << i;
    }
  }
  // A constant map does not vary; a point segment does not either.
  const bound::DisplacementMap flat("flat", 4, 4, std::vector<float>(16, 0.3f), 2.0, 0.5);
  EXPECT_EQ(flat.variationAlong({0.1, 0.2}, {0.9, 0.7}), 0.0);
  EXPECT_EQ(procedural(1.0).variationAlong({0.3, 0.3}, {0.3, 0.3}), 0.0);
  // A ramp across texel centres: exactly its rise times the scale.
  const bound::DisplacementMap ramp("ramp", 4, 1, {0.0f, 0.25f, 0.5f, 0.75f}, 2.0, 0.0);
  EXPECT_NEAR(ramp.variationAlong({0.125, 0.5}, {0.875, 0.5}), 2.0 * 0.75, 1e-12);
}

// One patch edge: its boundary curve's ends (for matching) and texture coordinates.
struct EdgeRef {
  uint32_t patch = 0;
  int edge = 0;
  glm::dvec3 from{}, to{};
  glm::dvec2 uvFrom{}, uvTo{};
  bool transition = false;
};

// Pairs of edges of different patches with the same ends (within `tolerance`), in either
// direction: the shared edges of a closed or bounded mesh.
std::vector<std::pair<EdgeRef, EdgeRef>> sharedEdges(const PatchExtraction& ex, double tolerance) {
  constexpr std::array<int, 4> kFrom = {0, 0, 1, 3}, kTo = {3, 1, 2, 2};
  constexpr std::array<uint32_t, 4> kTransitionBit = {8u, 1u, 2u, 4u};
  std::map<std::array<int64_t, 3>, std::vector<EdgeRef>> buckets;
  const auto key = [&](const glm::dvec3& p) {
    return std::array<int64_t, 3>{std::llround(p.x / (64 * tolerance)),
                                  std::llround(p.y / (64 * tolerance)),
                                  std::llround(p.z / (64 * tolerance))};
  };
  std::vector<std::pair<EdgeRef, EdgeRef>> pairs;
  for (uint32_t p = 0; p < ex.patches.patchCount(); ++p) {
    const auto cp = ex.patches.controlPoints(p);
    const auto curves = frame::edgeCurveIndices(ex.patches.type(p));
    for (int e = 0; e < 4; ++e) {
      EdgeRef r{p,
                e,
                cp[curves[e][0]],
                cp[curves[e][3]],
                ex.uvCorners[4 * p + kFrom[e]],
                ex.uvCorners[4 * p + kTo[e]],
                (ex.patches.params[p].GetTransition() & kTransitionBit[e]) != 0};
      auto& bucket = buckets[key(0.5 * (r.from + r.to))];
      for (const EdgeRef& o : bucket) {
        const bool same =
            glm::distance(o.from, r.from) < tolerance && glm::distance(o.to, r.to) < tolerance;
        const bool reversed =
            glm::distance(o.from, r.to) < tolerance && glm::distance(o.to, r.from) < tolerance;
        if (same)
          pairs.emplace_back(o, r);
        else if (reversed)
          pairs.emplace_back(
              o, EdgeRef{r.patch, r.edge, r.to, r.from, r.uvTo, r.uvFrom, r.transition});
      }
      bucket.push_back(r);
    }
  }
  return pairs;
}

struct SideComparison {
  uint32_t continuousEdges = 0;  ///< edge-views with the same texture coordinates both sides
  uint32_t mismatched = 0;       ///< of those, levels that differ
  double levelSum = 0.0;
};

SideComparison compareSides(const PatchExtraction& ex, const bound::DisplacementMap& map,
                            DisplacedTessellation mode, int views) {
  const auto displacement = frame::edgeDisplacements(map, ex.uvCorners, ex.patches.patchCount());
  const auto pairs = sharedEdges(ex, 1e-9 * frame::boundsOf(ex.patches.points).radius());
  frame::TessellationOptions t;
  t.mode = frame::TessellationOptions::Mode::Adaptive;
  t.pixelsPerSegment = 3.0;
  t.displaced = mode;
  t = frame::effectiveOptions(t, frame::hasTransitionEdges(ex.patches));
  const frame::Bounds bounds = frame::boundsOf(ex.patches.points);
  SideComparison out;
  for (int v = 0; v < views; ++v) {
    const double a = 0.9 * v + 0.3;
    const glm::dvec3 dir(std::cos(a), 0.4 * std::sin(2.0 * a), std::sin(a));
    const auto camera = frame::frameBounds(bounds, glm::normalize(dir), {0, 1, 0}, 40.0, 256, 256);
    std::vector<frame::PatchTessLevels> levels;
    for (uint32_t p = 0; p < ex.patches.patchCount(); ++p)
      levels.push_back(frame::patchTessLevels(ex.patches, p, camera.viewProjection(), {256, 256}, t,
                                              &displacement[p]));
    for (const auto& [a0, b0] : pairs) {
      if (a0.transition || b0.transition) continue;  // halves meet finer patches
      if (glm::vec2(a0.uvFrom) != glm::vec2(b0.uvFrom) || glm::vec2(a0.uvTo) != glm::vec2(b0.uvTo))
        continue;  // a UV seam: the sides read different texels
      ++out.continuousEdges;
      const double la = levels[a0.patch].lo[a0.edge], lb = levels[b0.patch].lo[b0.edge];
      out.mismatched += la != lb;
      out.levelSum += la;
    }
  }
  return out;
}

TEST(DisplacedTessellation, SharedEdgesGetTheSameLevelOnBothSides) {
  OSD_CULL_REQUIRE_DATA();
  for (const char* mesh : {"shapes/catmark_torus.obj", "characters/bigguy.obj"}) {
    SCOPED_TRACE(mesh);
    const PatchExtraction ex = extractPatches(adapters::loadCage(test::dataDir() / mesh));
    const auto map = procedural(0.05 * frame::boundsOf(ex.patches.points).radius());
    const SideComparison edge = compareSides(ex, map, DisplacedTessellation::EdgeVariation, 4);
    const SideComparison none = compareSides(ex, map, DisplacedTessellation::Ignore, 4);
    const SideComparison perPatch = compareSides(ex, map, DisplacedTessellation::PerPatch, 4);
    ASSERT_GT(edge.continuousEdges, 4 * ex.patches.patchCount());  // most edges matched
    EXPECT_EQ(edge.mismatched, 0u);
    EXPECT_EQ(none.mismatched, 0u);
    // The displacement raises the levels, and a per-patch term breaks the agreement: the
    // comparison above can fail.
    EXPECT_GT(edge.levelSum, 1.02 * none.levelSum);
    EXPECT_GT(perPatch.mismatched, edge.continuousEdges / 200);
  }
}

class DisplacedCrackTest : public test::VkTest {
 protected:
  struct Result {
    uint32_t cracks = 0;
    uint64_t tesInvocations = 0;
  };

  // Views from 45 degrees above the equator of a ring (axis z) around a closed displaced
  // mesh, adaptive levels, back faces culled: crack pixels (frame::countCracks, gaps up to
  // 5 pixels) and TES invocations summed over the views.
  Result drawViews(const PatchExtraction& ex, const bound::DisplacementMap& map,
                   DisplacedTessellation mode, int views, uint32_t size) {
    frame::GpuPatchSet gpu(context(), ex.patches);
    frame::GpuDisplacement displacement(context(), map, ex.uvCorners, ex.patches.patchCount());
    gpu.setDisplacement(&displacement);
    frame::RenderTarget target(context(), size, size);
    frame::Renderer renderer(context());
    frame::RenderOptions options;
    options.tessellation.mode = frame::TessellationOptions::Mode::Adaptive;
    options.tessellation.pixelsPerSegment = 4.0;
    options.tessellation.displaced = mode;
    const frame::PatchDraw draw{&gpu, &ex.patches, 0};
    const frame::Bounds bounds = frame::boundsOf(ex.patches.points);
    Result out;
    for (int v = 0; v < views; ++v) {
      const double a = 2.0 * v + 0.5;
      const glm::dvec3 dir(std::cos(a), std::sin(a), 1.0);
      const auto camera =
          frame::frameBounds(bounds, glm::normalize(dir), {0, 0, 1}, 40.0, size, size);
      out.cracks += frame::countCracks(context(), renderer, target, camera, draw, options, 3);
      out.tesInvocations += renderer.render(target, camera, gpu, &ex.patches, options)
                                .statistics.tessEvaluationInvocations;
    }
    return out;
  }
};

// A torus cage of n x m quads (axis z) whose texture coordinates run from 0 to 1 around
// both circles: its UV seams (s, t = 1 | 0) differ by whole periods, so a periodic map
// (the procedural one, sampled with repeat addressing) is continuous across every edge.
std::filesystem::path periodicTorus(const std::filesystem::path& dir, int n, int m) {
  const auto path = dir / "periodic_torus.obj";
  std::ofstream obj(path);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double theta = 2.0 * M_PI * i / n, phi = 2.0 * M_PI * j / m;
      const double r = 1.0 + 0.45 * std::cos(phi);
      obj << "v " << r * std::cos(theta) << " " << r * std::sin(theta) << " "
          << 0.45 * std::sin(phi) << "\n";
    }
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j) obj << "vt " << double(i) / n << " " << double(j) / m << "\n";
  const auto vertex = [&](int i, int j) { return (i % n) * m + (j % m) + 1; };
  const auto texture = [&](int i, int j) { return i * (m + 1) + j + 1; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      obj << "f";
      for (const auto& [a, b] : {std::pair{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}})
        obj << " " << vertex(a, b) << "/" << texture(a, b);
      obj << "\n";
    }
  return path;
}

TEST_F(DisplacedCrackTest, ContinuousMapLeavesNoCrackAndAMismatchedLevelDoes) {
  // A closed, all-regular mesh with a map continuous across every edge: both sides of
  // each edge hold the same boundary curve and texture coordinates (up to whole periods).
  test::TempDir dir("osd_cull_disp_tess_");
  const PatchExtraction ex = extractPatches(adapters::loadCage(periodicTorus(dir.path(), 8, 8)));
  ASSERT_EQ(ex.patches.gregoryCount, 0u);
  const auto map = procedural(0.06 * frame::boundsOf(ex.patches.points).radius());
  const Result edge = drawViews(ex, map, DisplacedTessellation::EdgeVariation, 6, 128);
  const Result perPatch = drawViews(ex, map, DisplacedTessellation::PerPatch, 6, 128);
  const Result none = drawViews(ex, map, DisplacedTessellation::Ignore, 6, 128);
  std::printf(
      "crack pixels over 6 views: edge %u, none %u, per-patch %u; TES invocations: "
      "edge %llu, none %llu\n",
      edge.cracks, none.cracks, perPatch.cracks,
      static_cast<unsigned long long>(edge.tesInvocations),
      static_cast<unsigned long long>(none.tesInvocations));
  EXPECT_EQ(edge.cracks, 0u) << "the inside seen through the surface";
  EXPECT_EQ(none.cracks, 0u);
  EXPECT_GT(perPatch.cracks, 0u) << "mismatched levels must open the surface";
  EXPECT_GT(edge.tesInvocations, none.tesInvocations) << "the displacement term adds vertices";
}

}  // namespace
}  // namespace osd_cull
