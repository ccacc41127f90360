// Clustered, hierarchical culling (bound/patch_clusters.h, CullSettings::clusters): every
// patch in one cluster, merges that the cost model says pay, cluster culls that are culls of
// every member (double reference and GPU), no pixel lost, and the per-patch kernel
// invocations they save on BigGuy at 1280x720 (docs/algorithms/clusters.md).
#include "osd_cull/bound/patch_clusters.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/frame/verify/visibility_oracle.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/scene/demo_shapes.h"
#include "support/cull_test_meshes.h"
#include "support/run_command.h"
#include "support/test_data.h"
#include "support/vk_test_context.h"

#include <osd_cull/shared/draw_layout.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numeric>

namespace osd_cull {
namespace {

using bound::ClusterVerdict;

// A sphere scaled by 1000 and moved 1e5 away: the margins are relative.
PatchSet farSphere() {
  PatchSet set = scene::bezierSphere({0, 0, 0}, 1.0, 12);
  for (glm::dvec3& p : set.points) p = p * 1000.0 + glm::dvec3(1e5, -2e5, 3e4);
  set.source = "far scaled sphere";
  return set;
}

TEST(PatchClusters, EveryPatchIsInExactlyOneClusterAndMergingPays) {
  const PatchSet set = scene::bezierSphere({0, 0, 0}, 1.0, 12);
  const auto cones = bound::buildPatchCones(set, bound::BackPatchMethod::TCone);
  const bound::PatchClusters c = bound::buildPatchClusters(set, cones);
  std::vector<uint32_t> members = c.members;
  std::sort(members.begin(), members.end());
  std::vector<uint32_t> all(set.patchCount());
  std::iota(all.begin(), all.end(), 0u);
  EXPECT_EQ(members, all);
  EXPECT_GT(c.clusters.size(), 1u);
  EXPECT_LT(c.clusters.size(), set.patchCount() / 4);
  EXPECT_LT(c.modelCost, c.perPatchCost);
  for (const bound::PatchCluster& k : c.clusters) {
    EXPECT_LE(k.size(), bound::ClusterCostModel{}.maxPatches);
    EXPECT_TRUE(k.coneValid);
    for (uint32_t i = k.first; i < k.first + k.size(); ++i) {
      const bound::ConeOfNormals& m = cones[c.members[i]];
      const double theta = std::acos(std::clamp(glm::dot(k.axis, m.axis), -1.0, 1.0));
      EXPECT_LE(theta + m.angle, k.angle + 1e-12) << "the cluster cone holds the member's";
    }
  }
  // A dearer cluster test merges more: fewer, larger clusters.
  bound::ClusterCostModel dear;
  dear.clusterTest = 8.0;
  EXPECT_LT(bound::buildPatchClusters(set, cones, dear).clusters.size(), c.clusters.size());
  EXPECT_THROW(bound::buildPatchClusters(set, std::span(cones).first(3)), Error);
}

// The double reference: a culled cluster's members are all culled by the per-patch reference
// (surface cone tests), an accepted cluster's all kept.
void expectReferenceSubset(const PatchSet& set, bound::BackPatchMethod method, uint32_t views,
                           const std::string& name) {
  const auto cones = bound::buildPatchCones(set, method);
  const bound::PatchClusters c = bound::buildPatchClusters(set, cones);
  bound::CullTests tests;
  tests.backPatch = method;
  bound::ClusterTests ct;
  ct.backPatch = true;
  ct.backCull = true;
  frame::ViewSetOptions vo;
  vo.count = views;
  vo.width = 1280;
  vo.height = 720;
  uint32_t culled = 0, accepted = 0;
  for (const frame::Camera& camera : frame::randomViews(frame::boundsOf(set.points), vo)) {
    const bound::CullView view = bound::makeCullView(camera.viewProjection());
    for (const bound::PatchCluster& k : c.clusters) {
      const bound::ClusterResult r = bound::testCluster(k, view, ct);
      if (r.verdict == ClusterVerdict::Undecided) continue;
      (r.verdict == ClusterVerdict::Accepted ? accepted : culled) += k.size();
      for (uint32_t i = k.first; i < k.first + k.size(); ++i) {
        const bound::CullCode code{bound::referenceCullCode(set, c.members[i], view, tests, cones)};
        EXPECT_EQ(code.culled(), r.verdict != ClusterVerdict::Accepted)
            << name << " patch " << c.members[i] << " " << bound::describe(code);
      }
    }
  }
  EXPECT_GT(culled, 0u) << name;
  EXPECT_GT(accepted, 0u) << name;
}

TEST(PatchClusters, ReferenceClusterVerdictsAgreeWithEveryMembersReference) {
  expectReferenceSubset(scene::bezierSphere({0, 0, 0}, 1.0, 12), bound::BackPatchMethod::TCone, 20,
                        "sphere");
  expectReferenceSubset(farSphere(), bound::BackPatchMethod::NCone, 20, "far sphere");
}

class ClusteredCullTest : public test::VkTest {};

struct Comparison {
  uint64_t patches = 0, invocations = 0, culledPerPatch = 0, culledClustered = 0;
  uint64_t clustersCulled = 0, clustersAccepted = 0, clustersUndecided = 0, clusterTests = 0;
  double msPerPatch = 0, msClustered = 0;
};

// Per view: the clustered pass's culls are a subset of the per-patch pass's culls.
Comparison comparePasses(vulkan::Context& context, const PatchSet& set,
                         frame::CullSettings settings, uint32_t views, const std::string& name) {
  frame::GpuPatchSet gpu(context, set);
  settings.staticPoints = true;
  frame::CullPass plain(context, gpu, set, settings);
  settings.clusters = true;
  frame::CullPass clustered(context, gpu, set, settings);
  frame::ViewSetOptions vo;
  vo.count = views;
  vo.width = 1280;
  vo.height = 720;
  frame::TessellationOptions tess;
  tess.uniformLevel = 4;
  Comparison out;
  for (const frame::Camera& camera : frame::randomViews(frame::boundsOf(set.points), vo)) {
    out.msPerPatch += plain.run(camera, tess);
    out.msClustered += clustered.run(camera, tess);
    const auto a = plain.results();
    const auto b = clustered.results();
    for (uint32_t p = 0; p < set.patchCount(); ++p) {
      const bound::CullCode ca{a[p]}, cb{b[p]};
      EXPECT_TRUE(!cb.culled() || ca.culled())
          << name << ": patch " << p << " culled by its cluster (" << bound::describe(cb)
          << ") but kept per patch (" << bound::describe(ca) << ")";
      out.culledPerPatch += ca.culled();
      out.culledClustered += cb.culled();
    }
    const frame::ClusterCounts k = clustered.clusterCounts();
    EXPECT_EQ(k.culled + k.accepted + k.undecided, k.clusters) << name;
    EXPECT_EQ(
        clustered.counts().survivors(),
        set.patchCount() - std::count_if(b.begin(), b.end(),
                                         [](uint32_t r) { return bound::CullCode{r}.culled(); }))
        << name << ": every kept patch is in the draw list once";
    out.patches += set.patchCount();
    out.invocations += k.perPatchInvocations;
    out.clustersCulled += k.culled;
    out.clustersAccepted += k.accepted;
    out.clustersUndecided += k.undecided;
    out.clusterTests += k.clusters;
  }
  std::printf(
      "%s: %u views, per-patch invocations %llu of %llu (%.1f%%), culls %llu clustered / %llu "
      "per patch, clusters culled %llu accepted %llu undecided %llu of %llu, cull ms %.3f "
      "clustered / %.3f per patch (mean)\n",
      name.c_str(), views, (unsigned long long)out.invocations, (unsigned long long)out.patches,
      100.0 * double(out.invocations) / double(out.patches),
      (unsigned long long)out.culledClustered, (unsigned long long)out.culledPerPatch,
      (unsigned long long)out.clustersCulled, (unsigned long long)out.clustersAccepted,
      (unsigned long long)out.clustersUndecided, (unsigned long long)out.clusterTests,
      out.msClustered / views, out.msPerPatch / views);
  return out;
}

TEST_F(ClusteredCullTest, ClusterCullsAreASubsetOfThePerPatchCullsOnRandomViews) {
  frame::CullSettings settings;
  settings.backPatch = "tcone";
  settings.backPatchValidity = {true, "closed sphere"};
  const Comparison a = comparePasses(context(), farSphere(), settings, 12, "far sphere, tcone");
  EXPECT_LT(a.invocations, a.patches);
  settings.drawnTriangles = false;
  settings.backPatch = "ncone";
  const Comparison b = comparePasses(context(), scene::bezierSphere({0, 0, 0}, 1.0, 12), settings,
                                     12, "sphere, ncone surface-exact");
  EXPECT_LT(b.invocations, b.patches / 2);
  EXPECT_GT(b.culledClustered, 0u);
  frame::CullSettings frustumOnly;
  const Comparison c = comparePasses(context(), scene::defaultScene().patches, frustumOnly, 12,
                                     "default scene, frustum");
  EXPECT_LT(c.invocations, c.patches);
}

TEST_F(ClusteredCullTest, BigGuyAt720pTestsFewerThanHalfThePatchesOneByOne) {
  OSD_CULL_REQUIRE_DATA();
  const test::CullMesh mesh = test::loadCullMesh(test::dataDir() / "characters" / "bigguy.obj", 2);
  ASSERT_TRUE(mesh.validity.enabled) << mesh.validity.reason;
  frame::CullSettings settings;
  settings.backPatch = "ncone";
  settings.backPatchValidity = mesh.validity;
  settings.drawnTriangles = false;
  const Comparison exact =
      comparePasses(context(), mesh.patches, settings, 10, "BigGuy 1280x720, ncone surface-exact");
  EXPECT_LE(2 * exact.invocations, exact.patches) << "the issue's target: at least 50% fewer";
  EXPECT_GT(exact.culledClustered, 0u);
  settings.drawnTriangles = true;
  const Comparison drawn = comparePasses(context(), mesh.patches, settings, 10,
                                         "BigGuy 1280x720, ncone drawn triangles");
  EXPECT_LT(drawn.invocations, drawn.patches);
}

// Over random views: pixels the full draw covers and the clustered frame leaves empty (the
// image check), and patches the clustered pass culls that have pixels in the pixel-exact
// oracle (frame/verify/visibility_oracle.h, drawn as the rasterizer culling back faces
// draws them; the drawn-triangle cone tests keep every such patch).
struct Violations {
  size_t lostPixels = 0;
  size_t falseCulls = 0;
};

Violations clusteredViolations(vulkan::Context& context, const PatchSet& set,
                               const std::string& method, uint32_t views) {
  frame::GpuPatchSet gpu(context, set);
  frame::CullSettings settings;
  settings.backPatch = method;
  settings.backPatchValidity = {true, "closed surfaces"};
  settings.staticPoints = true;
  settings.clusters = true;
  frame::CullPass pass(context, gpu, set, settings);
  frame::Renderer renderer(context);
  frame::VisibilityOracle oracle(context);
  frame::RenderTarget full(context, 480, 270), culled(context, 480, 270), items(context, 480, 270);
  frame::RenderOptions options;
  options.tessellation.uniformLevel = 4;
  options.cullBackFaces = true;
  frame::ViewSetOptions vo;
  vo.count = views;
  vo.width = 480;
  vo.height = 270;
  vo.set = frame::ViewSet::WholeObject;
  Violations v;
  for (const frame::Camera& camera : frame::randomViews(frame::boundsOf(set.points), vo)) {
    const frame::PatchDraw draw{&gpu, &set, 0};
    const auto a = renderer.render(full, camera, {&draw, 1}, {}, options);
    const auto b = frame::renderCulled(renderer, culled, camera, pass, {}, options);
    EXPECT_LT(b.patchesDrawn, a.patchesDrawn) << set.source;
    EXPECT_LT(pass.clusterCounts().perPatchInvocations, set.patchCount()) << set.source;
    const auto before = full.readItems(context), after = culled.readItems(context);
    for (size_t i = 0; i < before.size(); ++i)
      v.lostPixels += before[i] != shader::kItemBackground && after[i] == shader::kItemBackground;
    const frame::VisibilityCounts truth =
        oracle.query(renderer, items, camera, gpu, &set, {}, options.tessellation, 0, true);
    const auto codes = pass.results();
    for (uint32_t p = 0; p < set.patchCount(); ++p)
      v.falseCulls += bound::CullCode{codes[p]}.culled() && truth.visible(p);
  }
  return v;
}

TEST_F(ClusteredCullTest, ClusteredCullsHaveNoPixelInTheOracleAndLoseNoPixelOfTheFullDraw) {
  for (const auto& [set, method] :
       {std::pair{scene::defaultScene().patches, "tcone"}, std::pair{farSphere(), "ncone"}}) {
    const Violations v = clusteredViolations(context(), set, method, 6);
    EXPECT_EQ(v.lostPixels, 0u) << set.source;
    EXPECT_EQ(v.falseCulls, 0u) << set.source;
  }
}

TEST_F(ClusteredCullTest, ClusteredCullsOnBigGuyHaveNoPixelInTheOracle) {
  OSD_CULL_REQUIRE_DATA();
  const test::CullMesh mesh = test::loadCullMesh(test::dataDir() / "characters" / "bigguy.obj", 2);
  const Violations v = clusteredViolations(context(), mesh.patches, "ncone", 4);
  EXPECT_EQ(v.lostPixels, 0u);
  EXPECT_EQ(v.falseCulls, 0u);
}

TEST_F(ClusteredCullTest, UnsupportedConfigurationsAreNamedErrors) {
  const PatchSet set = scene::bezierSphere({0, 0, 0}, 1.0, 4);
  frame::GpuPatchSet gpu(context(), set);
  frame::CullSettings settings;
  settings.clusters = true;
  EXPECT_THROW(frame::CullPass(context(), gpu, set, settings), Error) << "without staticPoints";
  settings.staticPoints = true;
  settings.backPatch = "tangent-plane";
  settings.backPatchValidity = {true, "closed sphere"};
  EXPECT_THROW(frame::CullPass(context(), gpu, set, settings), Error) << "tangent plane";
  settings.backPatch = "tcone";
  EXPECT_NO_THROW(frame::CullPass(context(), gpu, set, settings));
}

TEST(ClustersCommand, RenderWithClustersDrawsTheSameAndReportsTheClusterTests) {
  namespace fs = std::filesystem;
  const fs::path program = test::osdCullProgram();
  if (!fs::exists(program)) GTEST_SKIP() << "osd-cull not built";
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "render_clusters_cli";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // --cull all has an occlusion stage, which clusters do not serve: a named error.
  const test::CommandResult bad =
      test::runCommand(program.string() + " render --out " + (dir / "bad.png").string() +
                       " --width 64 --height 64 --cull all --clusters");
  EXPECT_NE(bad.exitCode(), 0);
  EXPECT_NE(bad.output.find("occlusion"), std::string::npos) << bad.output;
  const auto runOnePass = [&](const std::string& name, const std::string& extra) {
    const test::CommandResult r = test::runCommand(
        program.string() + " render --out " + (dir / (name + ".png")).string() +
        " --width 320 --height 180 --frames 2 --orbit 60 --cull backpatch --backpatch-method "
        "tcone --validate --stats " +
        (dir / (name + ".json")).string() + extra);
    EXPECT_EQ(r.exitCode(), 0) << r.output;
    std::ifstream in(dir / (name + ".json"));
    return std::pair{r.output, nlohmann::json::parse(in)};
  };
  const auto [plainOut, plain] = runOnePass("plain", "");
  const auto [clusteredOut, clustered] = runOnePass("clustered", " --clusters");
  EXPECT_NE(clusteredOut.find("clusters "), std::string::npos) << clusteredOut;
  ASSERT_EQ(clustered["frames"].size(), 2u);
  for (size_t f = 0; f < 2; ++f) {
    const auto& a = plain["frames"][f];
    const auto& b = clustered["frames"][f];
    EXPECT_EQ(a["drawn"], b["drawn"]) << "frame " << f;
    EXPECT_FALSE(a.contains("clusters"));
    const uint32_t tests = b["clusters"]["tests"], culled = b["clusters"]["culled"],
                   accepted = b["clusters"]["accepted"], undecided = b["clusters"]["undecided"];
    EXPECT_GT(tests, 0u);
    EXPECT_EQ(culled + accepted + undecided, tests);
    EXPECT_LT(b["clusters"]["perPatchInvocations"].get<uint32_t>(), b["patches"].get<uint32_t>());
  }
}

TEST(ClustersCommand, VerifyWithClustersFindsNoViolation) {
  namespace fs = std::filesystem;
  const fs::path program = test::osdCullProgram();
  if (!fs::exists(program)) GTEST_SKIP() << "osd-cull not built";
  // verify exits non-zero on any violation (a cull outside the reference, a false cull in
  // the oracle, a lost pixel).
  const test::CommandResult r =
      test::runCommand(program.string() +
                       " verify --methods frustum,tcone,ncone --views 6 --width 320 --height 180 "
                       "--image-check --validate --clusters");
  EXPECT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_NE(r.output.find("ncone"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace osd_cull
