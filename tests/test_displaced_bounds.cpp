// Texture coordinates of patches (patch/face_varying_uv.h) and the displaced-patch bounds
// (bound/displaced_bounds.h): Full / ACoN / CoN applied to OOBB and CAF contain the
// displaced surface on dense sampling, for ordinary and extreme maps.
#include "adapters/load_mesh.h"
#include "osd_cull/bound/displaced_bounds.h"
#include "osd_cull/bound/frustum.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/camera.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/face_varying_uv.h"
#include "osd_cull/patch/patch_eval.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "support/displacement_test_maps.h"
#include "support/temp_dir.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <functional>

namespace {

using namespace osd_cull;
using bound::DisplacedBox;
using bound::DisplacedExtension;

constexpr DisplacedExtension kExtensions[] = {DisplacedExtension::Full, DisplacedExtension::ACoN,
                                              DisplacedExtension::CoN};
constexpr DisplacedBox kBoxes[] = {DisplacedBox::OOBB, DisplacedBox::CAF};

// A flat n x n grid of unit quads in z = 0 with texture coordinates equal to (x, y) / n,
// corners interpolated: its limit surface is the identity map of the grid.
CageMesh planarGrid(int n) {
  CageMesh m;
  m.source = "built-in:test-grid";
  m.boundary = BoundaryInterpolation::EdgeAndCorner;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      m.positions.emplace_back(x, y, 0.0);
      m.uvs.emplace_back(double(x) / n, double(y) / n);
    }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int v = y * (n + 1) + x;
      for (int k : {v, v + 1, v + n + 2, v + n + 1}) {
        m.faceVertices.push_back(k);
        m.faceUVs.push_back(k);
      }
      m.faceSizes.push_back(4);
    }
  return m;
}

glm::dvec2 bilinearUV(std::span<const glm::dvec2> c, double s, double t) {
  return (1 - s) * (1 - t) * c[0] + s * (1 - t) * c[1] + s * t * c[2] + (1 - s) * t * c[3];
}

TEST(PatchUVs, ObjTextureCoordinatesAreRead) {
  OSD_CULL_REQUIRE_DATA();
  const CageMesh cube = adapters::loadCage(test::dataDir() / "shapes/catmark_cube.obj");
  ASSERT_TRUE(cube.hasUVs());
  EXPECT_EQ(cube.uvs.size(), 14u);
  EXPECT_EQ(cube.faceUVs.size(), cube.faceVertices.size());
  const CageMesh pole = adapters::loadCage(test::dataDir() / "shapes/catmark_pole8.obj");
  EXPECT_FALSE(pole.hasUVs());
}

TEST(PatchUVs, ObjFaceCornersWithoutTextureCoordinatesDropTheChannel) {
  test::TempDir dir("osd_cull_uv_");
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
  const CageMesh relative =
      adapters::loadCage(dir.write("rel.obj", quad + "f 1/-4 2/-3 3/-2 4/-1\n"));
  ASSERT_TRUE(relative.hasUVs());
  EXPECT_EQ(relative.faceUVs, (std::vector<int>{0, 1, 2, 3}));
  const CageMesh partial = adapters::loadCage(dir.write("partial.obj", quad + "f 1/1 2/2 3 4/4\n"));
  EXPECT_FALSE(partial.hasUVs());
  EXPECT_TRUE(std::any_of(partial.notes.begin(), partial.notes.end(), [](const std::string& n) {
    return n.find("texture coordinate") != std::string::npos;
  }));
  EXPECT_THROW(adapters::loadCage(dir.write("bad.obj", quad + "f 1/9 2/2 3/3 4/4\n")), Error);
}

TEST(PatchUVs, FollowThePatchParameterisation) {
  // On a flat regular grid with texture coordinates (x, y) / n the limit surface is the
  // identity map, so the texture coordinates at (s, t) of every patch must equal the
  // patch's own position / n: this checks corner order and orientation of every patch.
  const int n = 6;
  PatchOptions options;
  options.isolationLevel = 2;
  const PatchExtraction ex = extractPatches(planarGrid(n), options);
  ASSERT_EQ(ex.uvCorners.size(), 4u * ex.patches.patchCount());
  for (uint32_t p = 0; p < ex.patches.patchCount(); ++p) {
    const auto c = std::span(ex.uvCorners).subspan(4 * size_t{p}, 4);
    for (double s : {0.0, 0.3, 1.0})
      for (double t : {0.0, 0.7, 1.0}) {
        const glm::dvec3 P = evaluatePatch(ex.patches, p, s, t).position;
        const glm::dvec2 uv = bilinearUV(c, s, t);
        ASSERT_NEAR(uv.x, P.x / n, 1e-9) << "patch " << p << " at " << s << ", " << t;
        ASSERT_NEAR(uv.y, P.y / n, 1e-9) << "patch " << p << " at " << s << ", " << t;
      }
  }
  EXPECT_EQ(ex.patches.gregoryCount, 0u);
}

TEST(PatchUVs, MeshWithoutTextureCoordinatesIsRefusedByName) {
  CageMesh grid = planarGrid(2);
  grid.uvs.clear();
  grid.faceUVs.clear();
  const PatchExtraction ex = extractPatches(grid);
  EXPECT_TRUE(ex.uvCorners.empty());
  bound::DisplacementMap map("flat", 4, 4, std::vector<float>(16, 0.5f), 1.0, 0.5);
  try {
    bound::buildDisplacedPatches(ex.patches, ex.uvCorners, map, DisplacedExtension::Full);
    FAIL() << "a map was applied to a mesh without texture coordinates";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("texture coordinates"), std::string::npos) << e.what();
  }
}

TEST(PatchUVs, SeamEdgesAreCounted) {
  OSD_CULL_REQUIRE_DATA();
  const PatchExtraction ex =
      extractPatches(adapters::loadCage(test::dataDir() / "shapes/catmark_cube.obj"));
  // The cube's unfolding (14 texture coordinates for 8 vertices) cuts 7 of its 12 edges;
  // each cut cage edge becomes several patch edges (4 at isolation level 2).
  EXPECT_EQ(countUVSeamEdges(ex.patches, ex.uvCorners), 7u * 4u);
  const std::vector<glm::dvec2> constant(ex.uvCorners.size(), glm::dvec2(0.5));
  EXPECT_EQ(countUVSeamEdges(ex.patches, constant), 0u);
}

// The displaced surface P + N D(uv) of a patch at (s, t), as the draw computes it (the
// normal of OpenSubdiv's derivatives); false where the normal is undefined.
bool displacedPoint(const PatchExtraction& ex, const bound::DisplacementMap& map, uint32_t p,
                    double s, double t, glm::dvec3& out) {
  const SurfacePoint sp = evaluatePatch(ex.patches, p, s, t);
  const glm::dvec3 n = glm::cross(sp.du, sp.dv);
  const double len = glm::length(n);
  if (!(len > 1e-12 * glm::length(sp.du) * glm::length(sp.dv)) || !(len > 0)) return false;
  const glm::dvec2 uv = bilinearUV(std::span(ex.uvCorners).subspan(4 * size_t{p}, 4), s, t);
  out = sp.position + (n / len) * map.displacement(map.sample(uv));
  return true;
}

using Shrink = std::function<void(bound::DisplacedPatch&)>;

// Counts dense samples of every patch outside its bound, over `views`, for one kernel.
size_t samplesOutside(const PatchExtraction& ex, const bound::DisplacementMap& map,
                      DisplacedExtension e, DisplacedBox b, std::span<const frame::Camera> views,
                      const Shrink& shrink = {}, int grid = 9) {
  std::vector<bound::DisplacedPatch> data =
      bound::buildDisplacedPatches(ex.patches, ex.uvCorners, map, e);
  if (shrink)
    for (auto& d : data) shrink(d);
  size_t outside = 0;
  for (const frame::Camera& cam : views)
    for (uint32_t p = 0; p < ex.patches.patchCount(); ++p) {
      const bound::DisplacedBound bd = bound::displacedBound(ex.patches.controlPoints(p), data[p],
                                                             e, b, cam.view, cam.projection);
      for (int i = 0; i < grid; ++i)
        for (int j = 0; j < grid; ++j) {
          glm::dvec3 q;
          if (displacedPoint(ex, map, p, double(i) / (grid - 1), double(j) / (grid - 1), q) &&
              !bound::boundContains(bd, q, cam.view))
            ++outside;
        }
    }
  return outside;
}

std::vector<frame::Camera> someViews(const PatchSet& patches, uint32_t count) {
  frame::ViewSetOptions options;
  options.count = count;
  options.width = 64;
  options.height = 64;
  return frame::randomViews(frame::boundsOf(patches.points), options);
}

void expectAllKernelsContain(const PatchExtraction& ex, const bound::DisplacementMap& map,
                             uint32_t viewCount, int grid = 7) {
  const auto views = someViews(ex.patches, viewCount);
  for (DisplacedExtension e : kExtensions)
    for (DisplacedBox b : kBoxes)
      EXPECT_EQ(samplesOutside(ex, map, e, b, views, {}, grid), 0u)
          << map.name() << " " << bound::displacedKernelName(e, b);
}

bound::DisplacementMap proceduralMap(double scale) {
  return bound::DisplacementMap("procedural", 64, 64, scene::proceduralDisplacementTexels(64, 3),
                                scale, 0.5);
}

TEST(DisplacedBounds, EveryKernelContainsTheDisplacedCreasedBoundaryShape) {
  OSD_CULL_REQUIRE_DATA();
  const PatchExtraction ex =
      extractPatches(adapters::loadCage(test::dataDir() / "shapes/catmark_single_crease.obj"));
  const double size = frame::boundsOf(ex.patches.points).radius();
  expectAllKernelsContain(ex, proceduralMap(0.1 * size), 6);
}

TEST(DisplacedBounds, EveryKernelContainsDisplacedBigGuy) {
  OSD_CULL_REQUIRE_DATA();
  PatchOptions options;
  options.isolationLevel = 1;
  const PatchExtraction ex =
      extractPatches(adapters::loadCage(test::dataDir() / "characters/bigguy.obj"), options);
  ASSERT_GT(ex.patches.gregoryCount, 0u);
  expectAllKernelsContain(ex, proceduralMap(1.0), 2, 4);
}

TEST(DisplacedBounds, EveryKernelContainsExtremeMaps) {
  OSD_CULL_REQUIRE_DATA();
  const PatchExtraction ex =
      extractPatches(adapters::loadCage(test::dataDir() / "shapes/catmark_cube.obj"));
  const auto maps = test::extremeDisplacementMaps(0.4);
  for (const auto& map : maps) expectAllKernelsContain(ex, map, 4);
}

TEST(DisplacedBounds, ADeliberatelyShrunkBoundFailsTheTest) {
  OSD_CULL_REQUIRE_DATA();
  const PatchExtraction ex =
      extractPatches(adapters::loadCage(test::dataDir() / "shapes/catmark_cube.obj"));
  const auto map = proceduralMap(0.5);
  const auto views = someViews(ex.patches, 2);
  const Shrink halve = [](bound::DisplacedPatch& d) {
    d.range.dmin *= 0.5;
    d.range.dmax *= 0.5;
  };
  for (DisplacedExtension e : kExtensions)
    for (DisplacedBox b : kBoxes)
      EXPECT_GT(samplesOutside(ex, map, e, b, views, halve), 0u)
          << bound::displacedKernelName(e, b);
  // A cone narrowed below the true normals fails too.
  const Shrink narrow = [](bound::DisplacedPatch& d) { d.cone.angle *= 0.25; };
  EXPECT_GT(samplesOutside(ex, map, DisplacedExtension::CoN, DisplacedBox::CAF, views, narrow), 0u);
}

TEST(DisplacedBounds, ConesNeverExtendMoreThanFull) {
  OSD_CULL_REQUIRE_DATA();
  const PatchExtraction ex =
      extractPatches(adapters::loadCage(test::dataDir() / "shapes/catmark_single_crease.obj"));
  const auto map = proceduralMap(0.3);
  const auto full =
      bound::buildDisplacedPatches(ex.patches, ex.uvCorners, map, DisplacedExtension::Full);
  size_t tighter = 0;
  for (DisplacedExtension e : {DisplacedExtension::ACoN, DisplacedExtension::CoN}) {
    const auto data = bound::buildDisplacedPatches(ex.patches, ex.uvCorners, map, e);
    for (uint32_t p = 0; p < ex.patches.patchCount(); ++p)
      for (glm::dvec3 axis : {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0.6, 0, 0.8)}) {
        const auto a = bound::axisExtension(data[p], e, axis);
        const auto f = bound::axisExtension(full[p], DisplacedExtension::Full, axis);
        ASSERT_LE(a.plus, f.plus);
        ASSERT_LE(a.minus, f.minus);
        tighter += a.plus < f.plus ? 1 : 0;
      }
  }
  EXPECT_GT(tighter, 0u);  // the cones do tighten something
}

TEST(DisplacedBounds, AxisExtensionFollowsThePaper) {
  // Cone around +z with half-angle 30 degrees, Dmax 2, Dmin -1.
  bound::DisplacedPatch d;
  d.range = {-1.0, 2.0};
  d.cone.valid = true;
  d.cone.axis = {0, 0, 1};
  d.cone.angle = glm::radians(30.0);
  const auto z = bound::axisExtension(d, DisplacedExtension::CoN, {0, 0, 1});
  EXPECT_NEAR(z.plus, 2.0, 1e-9);   // δ+ = 1
  EXPECT_NEAR(z.minus, 1.0, 1e-9);  // max(Dmax δ-, -Dmin δ+) = max(2 cos 150°, 1)
  const auto x = bound::axisExtension(d, DisplacedExtension::CoN, {2, 0, 0});  // |r| = 2
  EXPECT_NEAR(x.plus, 2.0 * 2.0 * std::cos(glm::radians(60.0)), 1e-8);
  EXPECT_NEAR(x.minus, 2.0 * 2.0 * std::cos(glm::radians(60.0)), 1e-8);
  const auto full = bound::axisExtension(d, DisplacedExtension::Full, {1, 0, 0});
  EXPECT_NEAR(full.plus, 2.0, 1e-9);
  EXPECT_NEAR(full.minus, 2.0, 1e-9);
}

}  // namespace
