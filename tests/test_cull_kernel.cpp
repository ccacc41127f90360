// The cull kernel (shaders/cull, frame/cull_pass): every method against its double
// reference, the result codes, the survivor list and indirect commands, per-mesh validity,
// non-finite input and the method registry.
#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/draw/render_target.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/vk/transfer.h"
#include "support/vk_test_context.h"

#include <osd_cull/shared/cull_layout.h>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <set>

namespace osd_cull {
namespace {

using bound::CullCode;
using frame::CullPass;
using frame::CullSettings;
namespace sh = shader;

const bound::BackPatchValidity kClosed{true, "closed test surface"};

// A closed sphere of Bézier patches, some turned into (equal-surface) Gregory patches.
PatchSet sphereWithGregory() {
  PatchSet s = scene::bezierSphere({0.2, -0.1, 0.3}, 1.5, 3);
  return scene::convertToGregory(s, [](uint32_t p) { return p % 7 == 3; });
}

CullSettings backPatchOnly(const std::string& method) {
  CullSettings s;
  s.frustum = false;
  s.backPatch = method;
  s.backPatchValidity = kClosed;
  return s;
}

class CullKernelTest : public test::VkTest {};

// Surface-exact tests (the papers' tests) on a coarse sphere, and the tests that respect the
// drawn triangles (the default, bound/drawn_triangles.h) on a finer one: at tessellation 4
// the chords of the coarse sphere's 30-degree patches deviate too far for them to cull much.
// `enumerate` adds the listed-triangle test (bound/drawn_triangle_set.h). Returns the GPU
// cull count per method.
std::map<std::string, uint64_t> expectSubsetOfReference(vulkan::Context& context,
                                                        bool drawnTriangles, double minRate,
                                                        bool enumerate = false,
                                                        uint32_t viewCount = 12) {
  const PatchSet set = drawnTriangles
                           ? scene::convertToGregory(scene::bezierSphere({0.2, -0.1, 0.3}, 1.5, 8),
                                                     [](uint32_t p) { return p % 7 == 3; })
                           : sphereWithGregory();
  frame::GpuPatchSet gpu(context, set);
  frame::ViewSetOptions vo;
  vo.count = viewCount;
  const auto views = frame::randomViews(frame::boundsOf(set.points), vo);
  std::map<std::string, uint64_t> culls;
  for (const std::string& method : frame::cullMethodNames(frame::CullStage::BackPatch)) {
    CullSettings settings = backPatchOnly(method);
    settings.drawnTriangles = drawnTriangles;
    settings.drawnEnumerate = enumerate;
    CullPass pass(context, gpu, set, settings);
    EXPECT_TRUE(pass.backPatchEnabled()) << method;
    uint64_t gpuCulled = 0, cpuCulled = 0, agree = 0, total = 0, gregoryCulled = 0;
    for (const auto& camera : views) {
      pass.run(camera);
      const auto results = pass.results();
      std::vector<bound::TriangleShape> shapes;
      const auto codes =
          bound::referenceCull(set, bound::makeCullView(camera.viewProjection()),
                               pass.referenceTests(camera, {}, shapes), pass.cones());
      for (uint32_t p = 0; p < set.patchCount(); ++p) {
        const CullCode g{results[p]}, c{codes[p]};
        EXPECT_TRUE(!g.culled() || c.culled())
            << method << " patch " << p << ": GPU " << bound::describe(g) << ", reference "
            << bound::describe(c);
        EXPECT_EQ(g.frustum(), sh::kNotRun);
        gpuCulled += g.culled();
        gregoryCulled += g.culled() && set.type(p) == PatchType::Gregory;
        cpuCulled += c.culled();
        agree += g.culled() == c.culled();
        ++total;
      }
    }
    // A closed sphere seen from outside faces away with about half its patches.
    EXPECT_GT(double(gpuCulled) / double(total), minRate) << method;
    EXPECT_GT(double(agree) / double(total), 0.97) << method;
    EXPECT_LE(gpuCulled, cpuCulled) << method;
    // Drawn triangles respected: only the listed test culls Gregory patches.
    if (drawnTriangles) {
      EXPECT_EQ(gregoryCulled > 0, enumerate) << method;
    }
    culls[method] = gpuCulled;
  }
  return culls;
}

TEST_F(CullKernelTest, EveryBackPatchMethodCullsASubsetOfItsReferenceAndCullsSomething) {
  expectSubsetOfReference(context(), false, 0.2);
}

TEST_F(CullKernelTest, DrawnTriangleBoundCullsASubsetOfItsReferenceAndCullsSomething) {
  expectSubsetOfReference(context(), true, 0.1);
}

// The listed-triangle test culls a subset of its reference, and more than the bound alone
// (it only ever adds culls to the bound's).
TEST_F(CullKernelTest, ListedDrawnTrianglesCullASubsetOfTheirReferenceAndMoreThanTheBound) {
  const auto bound = expectSubsetOfReference(context(), true, 0.1, false, 3);
  const auto listed = expectSubsetOfReference(context(), true, 0.1, true, 3);
  for (const auto& [method, n] : bound) {
    EXPECT_GT(listed.at(method), n) << method;
    std::printf("%s: bound %llu, listed %llu culls\n", method.c_str(), (unsigned long long)n,
                (unsigned long long)listed.at(method));
  }
}

TEST_F(CullKernelTest, TangentPlaneWithOneAndSixteenThreadsGiveTheSameVerdicts) {
  const PatchSet set = sphereWithGregory();
  frame::GpuPatchSet gpu(context(), set);
  CullSettings oneThread = backPatchOnly("tangent-plane");
  CullSettings sixteenThreads = backPatchOnly("tangent-plane-16");
  oneThread.drawnTriangles = sixteenThreads.drawnTriangles = false;  // many culls to compare
  CullPass one(context(), gpu, set, oneThread);
  CullPass sixteen(context(), gpu, set, sixteenThreads);
  frame::ViewSetOptions vo;
  vo.count = 8;
  vo.set = frame::ViewSet::WholeObject;
  uint64_t same = 0, total = 0, culled = 0;
  for (const auto& camera : frame::randomViews(frame::boundsOf(set.points), vo)) {
    one.run(camera);
    sixteen.run(camera);
    for (uint32_t p = 0; p < set.patchCount(); ++p) {
      same += one.results()[p] == sixteen.results()[p];
      culled += CullCode{one.results()[p]}.culled();
      ++total;
    }
  }
  // Only the summation order differs: verdicts may differ only within rounding.
  EXPECT_GE(same, total - total / 200);
  EXPECT_GT(culled, total / 4);
}

// A pass gives its draw set back to the patch set when it goes: a program (or a benchmark)
// that makes passes for many configurations over one patch set, in turn, never runs out of
// the patch set's kMaxDrawListSets, and each pass draws the patches it kept.
TEST_F(CullKernelTest, PassesGiveTheirDrawSetsBackWhenDestroyed) {
  const PatchSet set = scene::bezierSphere({0.2, -0.1, 0.3}, 1.5, 4);
  frame::GpuPatchSet gpu(context(), set);
  frame::Renderer renderer(context());
  frame::RenderTarget target(context(), 32, 32);
  const auto camera =
      frame::Camera::lookAt({0.2, -4.0, 0.3}, {0.2, -0.1, 0.3}, {0, 0, 1}, 40.0, 32, 32, 0.5, 20.0);
  frame::RenderOptions options;
  options.cullBackFaces = true;
  for (uint32_t i = 0; i < 2 * frame::GpuPatchSet::kMaxDrawListSets + 1; ++i) {
    CullPass pass(context(), gpu, set, backPatchOnly(i % 2 ? "ncone" : "tcone"));
    const frame::FrameStats stats = frame::renderCulled(renderer, target, camera, pass, {}, options);
    EXPECT_EQ(stats.patchesDrawn, pass.counts().survivors()) << "pass " << i;
    EXPECT_GT(stats.patchesDrawn, 0u) << "pass " << i;
    EXPECT_LT(stats.patchesDrawn, set.patchCount()) << "pass " << i;
  }
  // At once, the limit still holds and is named.
  std::vector<std::unique_ptr<CullPass>> live;
  for (uint32_t i = 0; i < frame::GpuPatchSet::kMaxDrawListSets; ++i) {
    live.push_back(std::make_unique<CullPass>(context(), gpu, set, backPatchOnly("ncone")));
    frame::renderCulled(renderer, target, camera, *live.back(), {}, options);
  }
  CullPass extra(context(), gpu, set, backPatchOnly("ncone"));
  EXPECT_THROW(frame::renderCulled(renderer, target, camera, extra, {}, options), Error);
}

TEST_F(CullKernelTest, SurvivorListAndIndirectCommandsMatchTheResultCodes) {
  PatchSet set = scene::bezierSphere({0.2, -0.1, 0.3}, 1.5, 8);  // 384 patches
  set = scene::convertToGregory(set, [](uint32_t p) { return p % 7 == 3; });
  frame::GpuPatchSet gpu(context(), set);
  CullSettings settings = backPatchOnly("ncone");
  settings.frustum = true;
  CullPass pass(context(), gpu, set, settings);
  // Looking at the sphere from close by with a narrow view: frustum and back-patch culls.
  const auto camera =
      frame::Camera::lookAt({0.2, -4.0, 0.3}, {0.9, -0.1, 0.3}, {0, 0, 1}, 30.0, 64, 64, 0.5, 20.0);
  frame::TessellationOptions tess;
  tess.uniformLevel = 16;  // 33^2 vertices per patch at transitions: 60 patches per draw
  pass.run(camera, tess);
  std::set<uint32_t> expected;
  uint32_t byStage[4] = {0, 0, 0, 0};
  for (uint32_t p = 0; p < set.patchCount(); ++p) {
    const CullCode c{pass.results()[p]};
    ++byStage[c.stage()];
    if (!c.culled()) expected.insert(p);
  }
  EXPECT_GT(byStage[sh::kStageFrustum], 0u);
  EXPECT_GT(byStage[sh::kStageBackPatch], 0u);
  EXPECT_GT(byStage[sh::kStageNone], 0u);
  const auto survivors = pass.survivors(context());
  EXPECT_EQ(std::set<uint32_t>(survivors.begin(), survivors.end()), expected);
  EXPECT_EQ(survivors.size(), expected.size());
  const frame::CullCounts counts = pass.counts();
  for (uint32_t i = 0; i < counts.survivorsBezier; ++i) EXPECT_LT(survivors[i], set.bezierCount);
  for (uint32_t i = counts.survivorsBezier; i < survivors.size(); ++i)
    EXPECT_GE(survivors[i], set.bezierCount);

  // Commands: consecutive runs of at most indirectDrawChunk slots covering the survivors.
  const uint32_t chunkB = frame::indirectDrawChunk(tess, kBezierPoints, set.bezierCount);
  const uint32_t chunkG = frame::indirectDrawChunk(tess, kGregoryPoints, set.gregoryCount);
  EXPECT_EQ(chunkB, 60u);
  EXPECT_EQ(counts.drawsBezier, (counts.survivorsBezier + chunkB - 1) / chunkB);
  EXPECT_EQ(counts.drawsGregory, (counts.survivorsGregory + chunkG - 1) / chunkG);
  const auto commands = vulkan::readback<VkDrawIndirectCommand>(context(), pass.commands());
  const uint32_t maxB = (set.bezierCount + chunkB - 1) / chunkB;
  uint32_t slots = 0;
  for (uint32_t i = 0; i < counts.drawsBezier; ++i) {
    EXPECT_EQ(commands[i].firstVertex, slots * 16);
    EXPECT_LE(commands[i].vertexCount, chunkB * 16);
    EXPECT_EQ(commands[i].instanceCount, 1u);
    slots += commands[i].vertexCount / 16;
  }
  EXPECT_EQ(slots, counts.survivorsBezier);
  slots = 0;
  for (uint32_t i = 0; i < counts.drawsGregory; ++i) {
    EXPECT_EQ(commands[maxB + i].firstVertex, (set.bezierCount + slots) * 20);
    slots += commands[maxB + i].vertexCount / 20;
  }
  EXPECT_EQ(slots, counts.survivorsGregory);
}

// Issue 24: the boxes CullSettings::staticPoints uploads hold every control point and are
// their box rounded outward to float (no looser), in the layout of shared/cull_layout.h.
TEST_F(CullKernelTest, PrecomputedPatchBoxesAreTheControlPointBoxesRoundedOutward) {
  PatchSet set = sphereWithGregory();
  set.points[set.firstPoint(5) + 3].y = std::numeric_limits<double>::quiet_NaN();
  const std::vector<float> boxes = frame::packPatchBoxes(set);
  const size_t n = set.patchCount();
  ASSERT_EQ(boxes.size(), n * sh::kBoxFloats);
  for (size_t c = 0; c < sh::kBoxFloats; ++c) EXPECT_TRUE(std::isnan(boxes[c * n + 5])) << c;
  for (uint32_t p = 0; p < n; ++p) {
    if (p == 5) continue;  // the non-finite patch: a NaN box, kept by the kernel
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const glm::dvec3& q : set.controlPoints(p)) {
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
    for (int c = 0; c < 3; ++c) {
      const float bLo = boxes[c * n + p], bHi = boxes[(3 + c) * n + p];
      EXPECT_LE(double(bLo), lo[c]) << "patch " << p;
      EXPECT_GE(double(bHi), hi[c]) << "patch " << p;
      // The nearest floats outward: the next float inward is inside the exact box.
      EXPECT_GT(double(std::nextafter(bLo, std::numeric_limits<float>::max())), lo[c]);
      EXPECT_LT(double(std::nextafter(bHi, -std::numeric_limits<float>::max())), hi[c]);
    }
  }
}

// With static points the frustum stage and the cones' drawn-triangle bound read the boxes:
// every cull is still a cull of the double reference, and they cull nearly what the
// control-point kernel culls (the box holds the hull; the bound's distance is the box's).
// The frustum-only pass (method "") has no back-patch stage.
TEST_F(CullKernelTest, StaticPointBoxesCullASubsetOfTheReferenceAndNearlyThePointKernels) {
  const PatchSet set = scene::convertToGregory(scene::bezierSphere({0.2, -0.1, 0.3}, 1.5, 8),
                                               [](uint32_t p) { return p % 7 == 3; });
  frame::GpuPatchSet gpu(context(), set);
  frame::ViewSetOptions vo;
  vo.count = 8;
  auto views = frame::randomViews(frame::boundsOf(set.points), vo);
  for (frame::Camera& camera : views)  // a narrow view: a third of the sphere is outside
    camera.projection = glm::scale(glm::dmat4(1.0), glm::dvec3(3.0, 3.0, 1.0)) * camera.projection;
  for (const std::string& method : {std::string("ncone"), std::string("tcone"), std::string()}) {
    CullSettings settings = backPatchOnly(method);
    settings.frustum = true;
    CullPass points(context(), gpu, set, settings);
    settings.staticPoints = true;
    CullPass boxes(context(), gpu, set, settings);
    EXPECT_FALSE(points.patchBoxes());
    EXPECT_TRUE(boxes.patchBoxes());
    uint64_t boxCulls = 0, pointCulls = 0, frustumCulls = 0;
    for (const auto& camera : views) {
      points.run(camera);
      boxes.run(camera);
      std::vector<bound::TriangleShape> shapes;
      const auto codes =
          bound::referenceCull(set, bound::makeCullView(camera.viewProjection()),
                               boxes.referenceTests(camera, {}, shapes), boxes.cones());
      for (uint32_t p = 0; p < set.patchCount(); ++p) {
        const CullCode b{boxes.results()[p]}, c{codes[p]};
        EXPECT_TRUE(!b.culled() || c.culled())
            << method << " patch " << p << ": GPU " << bound::describe(b) << ", reference "
            << bound::describe(c);
        boxCulls += b.culled();
        frustumCulls += b.stage() == sh::kStageFrustum;
        pointCulls += CullCode{points.results()[p]}.culled();
      }
    }
    EXPECT_GT(frustumCulls, set.patchCount() * views.size() / 10) << method;
    // The sphere's 384 patches are large and curved: their boxes lose ~10% of the hull's
    // frustum culls (fine meshes lose far less, docs/results/cull-kernel-floor.md).
    EXPECT_GE(double(boxCulls), 0.85 * double(pointCulls)) << method;
    EXPECT_LE(boxCulls, pointCulls + pointCulls / 100) << method;
  }
}

// The drawn-triangle kernels run without the listed-triangle test where it cannot list a
// patch (uniform levels above bound::kDrawnListLowLevel), and with it elsewhere.
TEST_F(CullKernelTest, TheLeanKernelRunsOnlyWhereNoPatchCanBeListed) {
  const PatchSet set = sphereWithGregory();
  frame::GpuPatchSet gpu(context(), set);
  CullPass pass(context(), gpu, set, backPatchOnly("ncone"));
  frame::TessellationOptions t;
  for (uint32_t level = 1; level <= 5; ++level) {
    t.uniformLevel = level;
    EXPECT_EQ(pass.leanKernelApplies(t), level > bound::kDrawnListLowLevel) << level;
  }
  t.uniformLevel = 8;
  t.maxLevel = 2;  // every edge at level 2: listable
  EXPECT_FALSE(pass.leanKernelApplies(t));
  t.maxLevel = 64;
  t.mode = frame::TessellationOptions::Mode::Adaptive;
  EXPECT_FALSE(pass.leanKernelApplies(t));
  // At a listable level (the full kernel) and above it (the lean one): every cull is a cull
  // of the reference.
  for (uint32_t level : {2u, 3u}) {
    frame::TessellationOptions u;
    u.uniformLevel = level;
    frame::ViewSetOptions vo;
    vo.count = 4;
    for (const auto& camera : frame::randomViews(frame::boundsOf(set.points), vo)) {
      pass.run(camera, u);
      std::vector<bound::TriangleShape> shapes;
      const auto codes = bound::referenceCull(set, bound::makeCullView(camera.viewProjection()),
                                              pass.referenceTests(camera, u, shapes), pass.cones());
      for (uint32_t p = 0; p < set.patchCount(); ++p)
        EXPECT_TRUE(!CullCode{pass.results()[p]}.culled() || CullCode{codes[p]}.culled())
            << "level " << level << " patch " << p;
    }
  }
}

TEST_F(CullKernelTest, BackPatchStageIsLeftOutWithTheReasonOnAnInvalidMesh) {
  const PatchSet set = sphereWithGregory();
  frame::GpuPatchSet gpu(context(), set);
  CullSettings settings = backPatchOnly("tangent-plane");
  settings.backPatchValidity = {false, "the surface is open (12 boundary edges)"};
  CullPass pass(context(), gpu, set, settings);
  EXPECT_FALSE(pass.backPatchEnabled());
  EXPECT_NE(pass.backPatchNote().find("12 boundary edges"), std::string::npos);
  const auto camera =
      frame::frameBounds(frame::boundsOf(set.points), {1, 0.3, 0.2}, {0, 0, 1}, 40.0, 64, 64);
  pass.run(camera);
  for (uint32_t r : pass.results()) EXPECT_EQ(r, sh::kResultInitial);
  EXPECT_EQ(pass.counts().survivors(), set.patchCount());
  // Without a stated validity, back-patch culling stays off.
  CullSettings unstated;
  unstated.backPatch = "tcone";
  EXPECT_FALSE(CullPass(context(), gpu, set, unstated).backPatchEnabled());
}

TEST_F(CullKernelTest, NonFiniteControlPointsAreKeptByEveryStage) {
  PatchSet set = sphereWithGregory();
  // Views from all around: each bad patch would otherwise be culled in some of them.
  frame::ViewSetOptions vo;
  vo.count = 6;
  std::vector<frame::Camera> views = frame::randomViews(frame::boundsOf(set.points), vo);
  views.push_back(frame::Camera::lookAt({0, 0, -6}, {0, 0, -10}, {0, 1, 0}, 40, 32, 32, 0.1, 9));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const uint32_t bad[] = {0, 5, set.bezierCount + 1};  // two Bézier, one Gregory
  set.points[set.firstPoint(bad[0]) + 5].y = nan;
  set.points[set.firstPoint(bad[1]) + 15].x = inf;
  set.points[set.firstPoint(bad[2]) + 7].z = -inf;
  frame::GpuPatchSet gpu(context(), set);
  for (const std::string& method : frame::cullMethodNames(frame::CullStage::BackPatch)) {
    CullSettings settings = backPatchOnly(method);
    settings.frustum = true;
    CullPass pass(context(), gpu, set, settings);
    for (const auto& camera : views) {
      pass.run(camera);
      for (uint32_t p : bad) {
        const CullCode c{pass.results()[p]};
        EXPECT_FALSE(c.culled()) << method << " patch " << p << ": " << bound::describe(c);
        EXPECT_EQ(c.frustum(), sh::kFrustumNonFinite) << method;
      }
    }
  }
  // With static points the frustum stage and the cones' bound read the boxes: NaN for these
  // patches (frame::packPatchBoxes), kept as well.
  for (const std::string& method : {std::string(), std::string("ncone")}) {
    CullSettings settings = backPatchOnly(method);
    settings.frustum = true;
    settings.staticPoints = true;
    CullPass pass(context(), gpu, set, settings);
    ASSERT_TRUE(pass.patchBoxes());
    for (const auto& camera : views) {
      pass.run(camera);
      for (uint32_t p : bad) {
        const CullCode c{pass.results()[p]};
        EXPECT_FALSE(c.culled()) << "static " << method << " patch " << p << ": "
                                 << bound::describe(c);
        EXPECT_EQ(c.frustum(), sh::kFrustumNonFinite) << "static " << method;
      }
    }
  }
}

TEST_F(CullKernelTest, UnknownOrMisplacedMethodsAreRejected) {
  const PatchSet set = scene::bezierSphere({0, 0, 0}, 1.0, 1);
  frame::GpuPatchSet gpu(context(), set);
  CullSettings s = backPatchOnly("tangent-plane-17");
  try {
    CullPass pass(context(), gpu, set, s);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("tangent-plane-16"), std::string::npos) << e.what();
  }
  s.backPatch = "frustum";
  EXPECT_THROW(CullPass(context(), gpu, set, s), Error);
}

// The fp64 cone kernels: the cull-region test in double with a tenth of the fp32 margin, so
// every fp32 cull is an fp64 cull (both are subsets of the reference, checked above).
TEST_F(CullKernelTest, Fp64ConeKernelsCullEveryPatchTheFp32KernelsCull) {
  if (!context().info().optional.shaderFloat64) GTEST_SKIP() << "no shaderFloat64";
  const PatchSet set = sphereWithGregory();
  frame::GpuPatchSet gpu(context(), set);
  frame::ViewSetOptions vo;
  vo.count = 8;
  const auto views = frame::randomViews(frame::boundsOf(set.points), vo);
  for (const std::string method : {"tcone", "ncone"}) {
    CullSettings fp32 = backPatchOnly(method), fp64 = backPatchOnly(method + "-fp64");
    fp32.drawnTriangles = fp64.drawnTriangles = false;  // many culls to compare
    CullPass single(context(), gpu, set, fp32), dbl(context(), gpu, set, fp64);
    uint64_t culled32 = 0, culled64 = 0;
    for (const auto& camera : views) {
      single.run(camera);
      dbl.run(camera);
      for (uint32_t p = 0; p < set.patchCount(); ++p) {
        const CullCode a{single.results()[p]}, b{dbl.results()[p]};
        EXPECT_TRUE(!a.culled() || b.culled()) << method << " patch " << p;
        culled32 += a.culled();
        culled64 += b.culled();
      }
    }
    EXPECT_GT(culled32, set.patchCount() * views.size() / 5) << method;
    EXPECT_GE(culled64, culled32) << method;
  }
}

TEST(CullKernel, Fp64MethodsNameTheMissingFeature) {
  auto log = std::make_shared<vulkan::ValidationLog>();
  vulkan::ContextOptions options = test::validatedContextOptions(log);
  options.adjustDeviceInfo = [](vulkan::DeviceInfo& info) { info.optional.shaderFloat64 = false; };
  vulkan::Context context(options);
  const PatchSet set = scene::bezierSphere({0, 0, 0}, 1.0, 1);
  frame::GpuPatchSet gpu(context, set);
  try {
    CullPass pass(context, gpu, set, backPatchOnly("tcone-fp64"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("shaderFloat64"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("tcone-fp64"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace osd_cull
