// Crack-free tessellation: closed surfaces drawn from many views show no holes, with
// uniform and adaptive levels, Bézier/Gregory neighbours and transition edges.
#include "adapters/load_mesh.h"
#include "osd_cull/scene/demo_shapes.h"
#include "adapters/image_png.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/frame/verify/crack_count.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"
#include "support/test_data.h"
#include "support/vk_test_context.h"
#include "support/vk_test_images.h"

#include <gtest/gtest.h>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

namespace osd_cull {
namespace {

using frame::RenderOptions;
using frame::TessellationOptions;

class CrackTest : public test::VkTest {
 protected:
  // Directions spread over the sphere (a few golden-angle spiral points).
  static std::vector<glm::dvec3> viewDirections(int n) {
    std::vector<glm::dvec3> dirs;
    for (int i = 0; i < n; ++i) {
      const double z = 1.0 - 2.0 * (i + 0.5) / n;
      const double r = std::sqrt(1.0 - z * z);
      const double phi = i * 2.399963229728653;
      dirs.push_back({r * std::cos(phi), z, r * std::sin(phi)});
    }
    return dirs;
  }

  static std::vector<RenderOptions> tessellations() {
    RenderOptions uniform;
    uniform.tessellation.uniformLevel = 3;
    uniform.cullBackFaces = true;
    RenderOptions adaptive = uniform;
    adaptive.tessellation.mode = TessellationOptions::Mode::Adaptive;
    adaptive.tessellation.pixelsPerSegment = 5.0;
    return {uniform, adaptive};
  }

  // Draws a closed set from many directions with back faces culled; returns the largest
  // number of holes found in any view: background pixels enclosed by the silhouette (for
  // convex sets), or else cracks (frame::countCracks, which also draws without culling).
  uint32_t worstHoles(const PatchSet& set, uint32_t size, int views, bool convex = true) {
    frame::GpuPatchSet gpu(context(), set);
    frame::RenderTarget target(context(), size, size);
    frame::Renderer renderer(context());
    const frame::Bounds bounds = frame::boundsOf(set.points);
    uint32_t worst = 0;
    for (const RenderOptions& options : tessellations())
      for (const glm::dvec3& dir : viewDirections(views)) {
        const glm::dvec3 up = std::abs(dir.y) > 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        const auto camera = frame::frameBounds(bounds, dir, up, 40.0, size, size);
        renderer.render(target, camera, gpu, &set, options);
        const auto items = target.readItems(context());
        uint32_t holes = 0;
        if (convex) {
          holes = test::countEnclosedBackground(items, size, size);
        } else {
          const auto depth = target.readDepth(context());
          RenderOptions unculled = options;
          unculled.cullBackFaces = false;
          renderer.render(target, camera, gpu, &set, unculled);
          holes = frame::countCracks(items, depth, target.readItems(context()), size, size);
          if (holes > worst) renderer.render(target, camera, gpu, &set, options);  // for the PNG
        }
        if (holes > worst) {
          worst = holes;
          const auto out = std::filesystem::path(OSD_CULL_BINARY_DIR) / "test_output";
          std::filesystem::create_directories(out);
          std::string name = std::filesystem::path(set.source).stem().string();
          std::replace_if(
              name.begin(), name.end(),
              [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
          adapters::writePng(out / ("crack_" + name + ".png"),
                          adapters::colorImage(size, size, target.readColor(context())));
        }
      }
    return worst;
  }
};

TEST_F(CrackTest, ClosedBezierSphereHasNoHolesFromAnyView) {
  EXPECT_EQ(worstHoles(scene::bezierSphere({0, 0, 0}, 1.0, 2), 128, 12), 0u);
}

TEST_F(CrackTest, SphereOfMixedBezierAndGregoryPatchesHasNoHoles) {
  const PatchSet mixed = scene::convertToGregory(scene::bezierSphere({0, 0, 0}, 1.0, 2),
                                                 [](uint32_t p) { return (p * 7) % 3 == 0; });
  ASSERT_GT(mixed.gregoryCount, 0u);
  ASSERT_GT(mixed.bezierCount, 0u);
  EXPECT_EQ(worstHoles(mixed, 128, 12), 0u);
}

TEST_F(CrackTest, ClosedShapesAndBigGuyExtractedFromOpenSubdivHaveNoHoles) {
  OSD_CULL_REQUIRE_DATA();
  // Patches as osd_cull/patch extracts them (isolation level 2, Gregory end caps):
  // transition edges around extraordinary vertices and creases, Bézier/Gregory neighbours.
  std::vector<std::filesystem::path> meshes = test::catmarkShapes();
  meshes.push_back(test::dataDir() / "characters" / "bigguy.obj");
  const std::vector<std::string> convexShapes = {
      "catmark_cube", "catmark_cube_corner0", "catmark_cube_creases0", "catmark_pyramid_creases0"};
  uint32_t drawn = 0;
  for (const auto& path : meshes) {
    const CageMesh cage = adapters::loadCage(path);
    if (!summarize(*makeTopologyRefiner(cage)).closed) continue;
    SCOPED_TRACE(path.filename().string());
    const PatchSet set = extractPatches(cage).patches;
    const bool convex = std::find(convexShapes.begin(), convexShapes.end(), path.stem().string()) !=
                        convexShapes.end();
    EXPECT_EQ(worstHoles(set, 96, 6, convex), 0u);
    ++drawn;
  }
  EXPECT_GE(drawn, 10u);
}

TEST_F(CrackTest, DetectorsFindADeliberateCrack) {
  // Pull one patch's shared edge inward: the gap it opens must be found by both
  // detectors, so the tests above can fail.
  PatchSet sphere = scene::bezierSphere({0, 0, 0}, 1.0, 2);
  for (uint32_t i : {0u, 1u, 2u, 3u}) sphere.points[i] *= 0.93;  // patch 0, edge v=0
  EXPECT_GT(worstHoles(sphere, 128, 12, true), 0u);
  PatchSet torus = scene::bsplineTorus({});
  for (uint32_t i : {1u, 2u}) torus.points[i] *= 0.97;  // patch 0, edge v=0 (inner points)
  EXPECT_GT(worstHoles(torus, 128, 12, false), 0u);
}

TEST_F(CrackTest, TorusWithTransitionEdgesHasNoCracks) {
  // One patch refined into four (depth 1), its neighbours with transition edges; half
  // the patches Gregory. Close-up views of the refined region fill the whole image, so
  // any background pixel is a crack.
  scene::TorusOptions o;
  o.nu = 8;
  o.nv = 6;
  o.refinePatch = 0;  // around theta = 0, phi = 0: the outer equator at (1.4, 0, 0)
  const PatchSet torus =
      scene::convertToGregory(scene::bsplineTorus(o), [](uint32_t p) { return p % 2 == 1; });
  frame::GpuPatchSet gpu(context(), torus);
  frame::RenderTarget target(context(), 96, 96);
  frame::Renderer renderer(context());
  // Targets on the refined patch's boundary (theta in [0, 45], phi in [0, 60] degrees):
  // its transition edges, their midpoints (where the children meet) and corners.
  const std::pair<double, double> targets[] = {{0, 30}, {45, 30}, {22.5, 0}, {22.5, 60},
                                               {0, 0},  {45, 60}, {22.5, 30}};
  for (const RenderOptions& options : tessellations()) {
    for (const auto& [thetaDeg, phiDeg] : targets) {
      const double theta = glm::radians(thetaDeg), phi = glm::radians(phiDeg);
      const glm::dvec3 normal(std::cos(phi) * std::cos(theta), std::cos(phi) * std::sin(theta),
                              std::sin(phi));
      const glm::dvec3 onSurface = glm::dvec3(std::cos(theta), std::sin(theta), 0.0) + 0.4 * normal;
      const glm::dvec3 tangent(-std::sin(theta), std::cos(theta), 0.0);
      const glm::dvec3 eye = onSurface + 0.15 * glm::normalize(normal + 0.3 * tangent);
      const glm::dvec3 up = glm::cross(normal, tangent);
      const auto camera = frame::Camera::lookAt(eye, onSurface, up, 30.0, 96, 96, 0.02, 10);
      renderer.render(target, camera, gpu, &torus, options);
      const auto histogram = test::itemHistogram(target.readItems(context()));
      if (histogram.count(0)) {
        const auto out = std::filesystem::path(OSD_CULL_BINARY_DIR) / "test_output";
        std::filesystem::create_directories(out);
        adapters::writePng(out / ("crack_torus_" + std::to_string(int(thetaDeg)) + "_" +
                               std::to_string(int(phiDeg)) + ".png"),
                        adapters::colorImage(96, 96, target.readColor(context())));
      }
      EXPECT_EQ(histogram.count(0), 0u)
          << "background pixels (cracks) looking at theta " << thetaDeg << ", phi " << phiDeg;
      EXPECT_GE(histogram.size(), 2u);  // patches meet in view
    }
  }
}

}  // namespace
}  // namespace osd_cull
