// The bounds pass (frame/cull/bounds_pass.h) against the double reference, and the cage
// input of DynamicPatchMesh (frame/dynamic_patch_mesh.h): CPU and GPU point updates, ranges,
// bad input, and no work for a static mesh; the displaced output (issue 11) the same way.
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/bounds_pass.h"
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/frame/dynamic_patch_mesh.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/cage_animation.h"
#include "osd_cull/scene/procedural.h"
#include "osd_cull/vk/transfer.h"
#include "support/bounds_check.h"
#include "support/displacement_test_maps.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

namespace osd_cull {
namespace {

using bound::BackPatchMethod;

// A sphere of Bézier patches (every fifth a Gregory patch), its points moved by a twist, a
// bend and per-point noise: many differently shaped patches, some with wide cones.
PatchSet randomDeformedPatches(uint32_t seed, double noise, const glm::dvec3& offset) {
  PatchSet set = scene::convertToGregory(scene::bezierSphere({0.0, 0.0, 0.0}, 1.0, 8),
                                         [](uint32_t p) { return p % 5 == 2; });
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  const double twist = uni(rng), bend = 0.5 * uni(rng);
  const glm::dvec3 stretch(1.0 + 0.5 * uni(rng), 1.0 + 0.5 * uni(rng), 1.0 + 0.5 * uni(rng));
  for (glm::dvec3& p : set.points) {
    const double a = twist * p.y;
    glm::dvec3 q(p.x * std::cos(a) - p.z * std::sin(a), p.y, p.x * std::sin(a) + p.z * std::cos(a));
    q.x += bend * q.y * q.y;
    q = q * stretch + noise * glm::dvec3(uni(rng), uni(rng), uni(rng)) + offset;
    p = q;
  }
  return set;
}

double floatPointError(const PatchSet& set) {
  double m = 0.0;
  for (const glm::dvec3& p : set.points)
    m = std::max({m, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  return 1.01 * m / 16777216.0;
}

class BoundsPassTest : public test::VkTest {};

test::BoundsCheck runAndCheck(vulkan::Context& context, frame::GpuPatchSet& gpu,
                              frame::BoundsPass& pass, const PatchSet& set, float shrink = 0.0f) {
  gpu.updatePoints(context, set.points);
  pass.run(floatPointError(set), shrink);
  return test::checkBounds(set, pass.method(), pass.readBounds(context));
}

TEST_F(BoundsPassTest, GpuBoundsContainTheDoubleReferenceOnRandomDeformedPatches) {
  frame::GpuPatchSet gpu(context(), randomDeformedPatches(0, 0.0, glm::dvec3(0.0)));
  // The tangent plane's data: the Gregory TCONE and, for Bézier patches, G and H only.
  for (BackPatchMethod method :
       {BackPatchMethod::TCone, BackPatchMethod::NCone, BackPatchMethod::TangentPlane}) {
    frame::BoundsPass pass(context(), gpu, method);
    test::BoundsCheck total;
    for (uint32_t seed = 1; seed <= 4; ++seed) {
      const glm::dvec3 offset = seed == 4 ? glm::dvec3(1e3, -2e2, 5e2) : glm::dvec3(0.0);
      const PatchSet set = randomDeformedPatches(seed, 0.003 * seed, offset);
      const test::BoundsCheck c = runAndCheck(context(), gpu, pass, set);
      for (const std::string& v : c.firstViolations) ADD_FAILURE() << toString(method) << ": " << v;
      std::printf("%s seed %u: %u valid on both, %u lost\n", toString(method), seed, c.bothValid,
                  c.lost);
      total.patches += c.patches;
      total.violations += c.violations;
      total.bothValid += c.bothValid;
      total.lost += c.lost;
      total.containsReference += c.containsReference;
      total.minAngleExcess = std::min(total.minAngleExcess, c.minAngleExcess);
      total.maxAngleExcess = std::max(total.maxAngleExcess, c.maxAngleExcess);
    }
    EXPECT_EQ(total.violations, 0u) << toString(method);
    // Looser, but not useless: most cones the reference finds survive in fp32 (the tangent
    // plane has cones for its Gregory patches only, every fifth).
    const uint32_t withCones =
        method == BackPatchMethod::TangentPlane ? total.patches / 5 : total.patches;
    EXPECT_GT(total.bothValid, withCones / 2) << toString(method);
    EXPECT_LT(total.lost, total.patches / 50 + 1) << toString(method);
    std::printf(
        "%s: %u patches, %u valid on both, %u lost, %u contain the reference cone, "
        "half-angle - reference in [%.3g, %.3g] rad\n",
        toString(method), total.patches, total.bothValid, total.lost, total.containsReference,
        total.minAngleExcess, total.maxAngleExcess);
  }
}

TEST_F(BoundsPassTest, DeliberatelyShrunkBoundsAreCaught) {
  // The check can fail: bounds made tighter by 2e-3 (sine of the half-angle, relative G/H)
  // must violate the reference somewhere.
  const PatchSet set = randomDeformedPatches(7, 0.0, glm::dvec3(0.0));
  frame::GpuPatchSet gpu(context(), set);
  for (BackPatchMethod method :
       {BackPatchMethod::TCone, BackPatchMethod::NCone, BackPatchMethod::TangentPlane}) {
    frame::BoundsPass pass(context(), gpu, method);
    EXPECT_EQ(runAndCheck(context(), gpu, pass, set).violations, 0u) << toString(method);
    EXPECT_GT(runAndCheck(context(), gpu, pass, set, 2e-3f).violations, 0u) << toString(method);
  }
}

TEST_F(BoundsPassTest, NonFinitePointsGiveAnInvalidConeNotACrash) {
  PatchSet set = randomDeformedPatches(3, 0.0, glm::dvec3(0.0));
  set.points[5].x = std::numeric_limits<double>::quiet_NaN();  // Bézier 0
  set.points[set.firstPoint(set.bezierCount) + 3].y = std::numeric_limits<double>::infinity();
  frame::GpuPatchSet gpu(context(), set);
  frame::BoundsPass pass(context(), gpu, BackPatchMethod::NCone);
  pass.run(floatPointError(randomDeformedPatches(3, 0.0, glm::dvec3(0.0))));
  const auto b = pass.readBounds(context());
  EXPECT_FALSE(b[0].cone.valid);
  EXPECT_EQ(b[0].cone.reason, bound::BackPatchVerdict::NonFinite);
  EXPECT_FALSE(b[set.bezierCount].cone.valid);
  EXPECT_TRUE(b[1].cone.valid || b[1].cone.reason != bound::BackPatchVerdict::NonFinite);
  EXPECT_THROW(frame::BoundsPass(context(), gpu, BackPatchMethod::None), Error);
  EXPECT_THROW(pass.readDisplaced(context()), Error);
  EXPECT_THROW(pass.run(-1.0), Error);
}

// Random Dmin <= 0 <= Dmax per patch (some zero on one side).
std::vector<bound::DisplacementRange> randomRanges(uint32_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 0.2);
  std::vector<bound::DisplacementRange> out(count);
  for (uint32_t p = 0; p < count; ++p)
    out[p] = {p % 7 == 3 ? 0.0 : -uni(rng), p % 11 == 4 ? 0.0 : uni(rng)};
  return out;
}

const bound::DisplacedExtension kExtensions[] = {bound::DisplacedExtension::Full,
                                                 bound::DisplacedExtension::ACoN,
                                                 bound::DisplacedExtension::CoN};

// Issue 11, animated displaced meshes: the cones of ACoN and CoN recomputed on the GPU
// from moved points hold every normal of the exact (double) patch, next to Dmin/Dmax.
TEST_F(BoundsPassTest, DisplacedConesContainTheDoubleReferenceOnRandomDeformedPatches) {
  const PatchSet first = randomDeformedPatches(0, 0.0, glm::dvec3(0.0));
  frame::GpuPatchSet gpu(context(), first);
  const auto ranges = randomRanges(first.patchCount(), 5);
  for (bound::DisplacedExtension extension : kExtensions) {
    frame::BoundsPass pass(context(), gpu, extension, ranges);
    EXPECT_TRUE(pass.displaced());
    EXPECT_EQ(pass.dependsOnPoints(), extension != bound::DisplacedExtension::Full);
    uint32_t bothValid = 0, caught = 0;
    constexpr float kShrink = 0.02f;
    for (uint32_t seed = 1; seed <= 3; ++seed) {
      const glm::dvec3 offset = seed == 3 ? glm::dvec3(1e3, -2e2, 5e2) : glm::dvec3(0.0);
      const PatchSet set = randomDeformedPatches(seed, 0.003 * seed, offset);
      gpu.updatePoints(context(), set.points);
      pass.run(floatPointError(set));
      const auto data = pass.readDisplaced(context());
      const test::BoundsCheck c = test::checkDisplacedBounds(set, extension, ranges, data);
      EXPECT_EQ(c.violations, 0u) << toString(extension) << " seed " << seed;
      for (const std::string& v : c.firstViolations)
        ADD_FAILURE() << toString(extension) << ": " << v;
      EXPECT_LT(c.lost, c.patches / 50 + 1) << toString(extension);
      bothValid += c.bothValid;
      // Shrunk cones must be caught (Full has none to shrink). The displaced check has only
      // the sampled normals (and CoN's coefficients) to catch them with, not the apex, G and
      // H of the back-patch data, so the shrink is larger than there.
      if (extension != bound::DisplacedExtension::Full) {
        pass.run(floatPointError(set), kShrink);
        caught += test::checkDisplacedBounds(set, extension, ranges, pass.readDisplaced(context()))
                      .violations;
      }
    }
    if (extension != bound::DisplacedExtension::Full) {
      EXPECT_GT(bothValid, 3 * first.patchCount() / 2) << toString(extension);
      EXPECT_GT(caught, 0u) << toString(extension) << ": cones shrunk by " << kShrink;
      std::printf("%s: %u violations with the cones shrunk by %g\n", toString(extension), caught,
                  double(kShrink));
    }
  }
  EXPECT_THROW(
      frame::BoundsPass(context(), gpu, bound::DisplacedExtension::CoN, std::span(ranges).first(3)),
      Error);
  auto bad = ranges;
  bad[2].dmin = 0.5;  // Dmin > 0
  try {
    frame::BoundsPass(context(), gpu, bound::DisplacedExtension::ACoN, bad);
    ADD_FAILURE() << "a range with Dmin > 0 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("patch 2"), std::string::npos) << e.what();
  }
}

TEST_F(BoundsPassTest, StaticMeshRunsNoUpdateAfterItsFirstFrame) {
  const CageMesh cage = test::withPlanarUVs(scene::defaultMesh());
  PatchExtraction ex = extractPatches(cage);
  const std::vector<glm::dvec2> uvCorners = ex.uvCorners;
  frame::DynamicPatchMesh mesh(context(), std::move(ex), cage.positions);
  const bound::DisplacementMap map("flat", 2, 2, {0.0f, 1.0f, 0.5f, 0.25f}, 0.1, 0.5);
  mesh.cullData(BackPatchMethod::TCone);
  mesh.cullData(BackPatchMethod::NCone);
  mesh.cullData(BackPatchMethod::TangentPlane);
  mesh.displacedCullData(map, uvCorners, bound::DisplacedExtension::CoN);
  mesh.displacedCullData(map, uvCorners, bound::DisplacedExtension::Full);
  EXPECT_NE(mesh.displacedBoundsPass(bound::DisplacedExtension::CoN), nullptr);
  EXPECT_EQ(mesh.displacedBoundsPass(bound::DisplacedExtension::ACoN), nullptr);
  const frame::DynamicMeshCounters first = mesh.counters();
  EXPECT_EQ(first.boundsDispatches, 5u);  // each method once, when first asked for
  for (int frame = 0; frame < 5; ++frame) EXPECT_FALSE(mesh.update());
  EXPECT_EQ(mesh.counters().pointUpdates, first.pointUpdates);
  EXPECT_EQ(mesh.counters().boundsDispatches, first.boundsDispatches);
  // A moved cage runs both again, once.
  std::vector<glm::dvec3> moved(mesh.cage().begin(), mesh.cage().end());
  moved[0].x += 0.1;
  mesh.setCagePositions(moved);
  EXPECT_TRUE(mesh.update());
  EXPECT_FALSE(mesh.update());
  EXPECT_EQ(mesh.counters().pointUpdates, first.pointUpdates + 1);
  // All but the displaced Full pass, whose Dmin/Dmax do not move with the cage.
  EXPECT_EQ(mesh.counters().boundsDispatches, first.boundsDispatches + 4);
  EXPECT_THROW(mesh.displacedCullData(map, {}, bound::DisplacedExtension::ACoN), Error);
}

TEST_F(BoundsPassTest, CpuAndGpuPointUpdatesAgreeAndTheirBoundsContainTheReference) {
  const CageMesh cage = scene::defaultMesh();
  scene::DeformerParams p;
  p.amount = 0.6;
  const auto twist = scene::makeTwist(cage.positions, p);
  std::vector<glm::dvec3> moved(cage.positions.size());
  twist->positions(0.5, moved);
  for (frame::PointUpdatePath path : {frame::PointUpdatePath::Cpu, frame::PointUpdatePath::Gpu}) {
    frame::DynamicPatchMesh mesh(context(), cage, {}, path);
    mesh.cullData(BackPatchMethod::TCone);
    mesh.setCagePositions(moved);
    ASSERT_TRUE(mesh.update());
    const PatchSet& host = mesh.patches();  // double, from the moved cage
    const std::vector<float> device = vulkan::readback<float>(context(), mesh.gpu().points());
    const uint32_t stride = mesh.gpu().pointStride(), offset = mesh.gpu().pointOffset();
    double worst = 0.0;
    for (size_t i = 0; i < host.points.size(); ++i)
      for (int k = 0; k < 3; ++k)
        worst =
            std::max(worst, std::abs(double(device[offset + i * stride + k]) - host.points[i][k]));
    EXPECT_LE(worst, mesh.pointError()) << toString(path);
    EXPECT_GT(worst, 0.0) << toString(path);  // float points: not a copy of the reference
    const test::BoundsCheck c =
        test::checkBounds(host, BackPatchMethod::TCone,
                          mesh.boundsPass(BackPatchMethod::TCone)->readBounds(context()));
    EXPECT_EQ(c.violations, 0u) << toString(path);
    for (const std::string& v : c.firstViolations) ADD_FAILURE() << v;
  }
}

TEST_F(BoundsPassTest, CageInputTakesRangesAndFloatsAndRejectsBadInput) {
  const CageMesh cage = scene::cube();
  frame::DynamicPatchMesh mesh(context(), cage);
  const std::vector<glm::dvec3> two = {{5, 5, 5}, {6, 6, 6}};
  mesh.setCagePositions(two, 3);
  EXPECT_TRUE(mesh.cageMoved());
  EXPECT_EQ(mesh.cage()[3], two[0]);
  EXPECT_EQ(mesh.cage()[4], two[1]);
  EXPECT_EQ(mesh.cage()[2], cage.positions[2]);
  const std::vector<float> xyz = {1.5f, 2.5f, 3.5f};
  mesh.setCagePositions(xyz, 7);
  EXPECT_EQ(mesh.cage()[7], glm::dvec3(1.5, 2.5, 3.5));
  EXPECT_THROW(mesh.setCagePositions(two, 7), Error);  // [7, 9) past 8 vertices
  EXPECT_THROW(mesh.setCagePositions(std::vector<float>{1.0f, 2.0f}, 0), Error);
  const std::vector<glm::dvec3> nan = {{0, std::numeric_limits<double>::quiet_NaN(), 0}};
  try {
    mesh.setCagePositions(nan, 2);
    ADD_FAILURE() << "NaN accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 2"), std::string::npos) << e.what();
  }
  EXPECT_EQ(mesh.cage()[2], cage.positions[2]);  // unchanged
  EXPECT_TRUE(mesh.update());
  // The cube's patches follow: every patch point is a combination of the moved cage.
  std::vector<glm::dvec3> expected(mesh.patches().points.size());
  mesh.matrix().update(mesh.cage(), expected);
  EXPECT_EQ(mesh.patches().points, expected);
}

}  // namespace
}  // namespace osd_cull
