// The effect plan applied to a scene (issue 12, scene form; docs/algorithms/plan.md
// "Scenes"): session::ScenePlayer with a planner plans every (view, instance) each frame and
// applies it. Deterministic through the synthetic calibration (support/plan_calibration.h):
// a static instance makes no point update and no bounds dispatch while an animated one does;
// an undisplaced instance builds and binds no displacement variant while a displaced one
// does; a far-away instance gets culling switched off while a close one gets it on, in the
// same scene and frame; `osd-cull plan SCENE` (plan::scenePlanInputs) agrees with what the
// player applies at frame 0; and every planned frame has zero false culls against the
// item-buffer oracle and loses no pixel against the unculled draw.
#include "adapters/scene_assets.h"
#include "adapters/scene_file.h"
#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/verify/item_comparison.h"
#include "osd_cull/frame/verify/visibility_oracle.h"
#include "osd_cull/plan/planner.h"
#include "osd_cull/plan/scene_inputs.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/session/scene_player.h"
#include "support/plan_calibration.h"
#include "support/process_memory.h"
#include "support/run_command.h"
#include "support/temp_dir.h"
#include "support/test_data.h"
#include "support/test_scenes.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <set>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;

scene::LoadedScene sceneFromText(const std::string& text) {
  return adapters::loadScene(adapters::parseScene(text, "test scene", test::dataDir()));
}

// BigGuy close to the camera, crossing the view's left edge, and a small torus far away in
// the middle of the view. (Tessellation is uniform over a scene: the far instance is the
// cheap one by its patch count, what a far, coarsely tessellated mesh is to the cost model.)
std::string nearFarScene() {
  const std::string guy = (test::dataDir() / "characters/bigguy.obj").string();
  return R"({"version": 1,
  "settings": {"frameCount": 2, "width": 128, "height": 96},
  "meshes": [{"name": "guy", "file": ")" +
         guy + R"(", "level": 1},
             {"name": "torus", "builtIn": "torus", "level": 1}],
  "instances": [{"name": "near", "mesh": "guy", "transform": {"translate": [-2.2, -3.0, 0], "scale": 0.04}},
                {"name": "far", "mesh": "torus", "transform": {"translate": [0, 60, 0]}}],
  "views": [{"name": "main", "camera": {"eye": [0, -8, 0], "target": [0, 0, 0]}}]})";
}

frame::CullFrameOptions planOptions(uint32_t tess) {
  frame::CullFrameOptions o;
  o.render.tessellation.uniformLevel = tess;
  o.render.cullBackFaces = true;
  o.cull.backPatch = "tcone";
  return o;
}

std::string describe(const std::vector<plan::Plan>& plans) { return plan::planTable(plans); }

class ScenePlan : public test::VkTest {
 protected:
  // Every view of the player's current frame against the item-buffer oracle of the unculled
  // draw (a culled patch with pixels is a false cull) and against the unculled image.
  void expectExact(session::ScenePlayer& player, const std::vector<session::ViewFrame>& views,
                   uint32_t f);
};

void ScenePlan::expectExact(session::ScenePlayer& player,
                            const std::vector<session::ViewFrame>& views, uint32_t f) {
  frame::VisibilityOracle oracle(context());
  for (size_t v = 0; v < views.size(); ++v) {
    frame::RenderTarget& culled = player.target(v);
    frame::RenderTarget plain(context(), culled.width(), culled.height());
    const session::UnculledComparison c = player.compareWithUnculled(v, plain);
    EXPECT_EQ(c.items.lost, 0u) << views[v].view << " frame " << f;
    EXPECT_LE(c.items.differing, c.items.pixels / 10000) << views[v].view << " frame " << f;
    if (!views[v].culled) continue;
    const frame::VisibilityCounts counts = oracle.count(plain, player.patchCount());
    uint32_t base = 0, falseCulls = 0, culledPatches = 0;
    for (size_t i = 0; i < player.instanceCount(); ++i) {
      const std::vector<uint32_t> codes = player.cullFrame(v).readResults(i);
      for (uint32_t p = 0; p < codes.size(); ++p)
        if (bound::CullCode{codes[p]}.stage() != 0) {
          ++culledPatches;
          falseCulls += counts.visible(base + p);
        }
      base += uint32_t(codes.size());
    }
    EXPECT_EQ(falseCulls, 0u) << views[v].view << " frame " << f;
    std::printf("%s frame %u: %u patches culled, %u false culls, %llu pixels lost\n",
                views[v].view.c_str(), f, culledPatches, falseCulls,
                static_cast<unsigned long long>(c.items.lost));
  }
}

TEST_F(ScenePlan, StaticInstanceMakesNoPointUpdateAndNoBoundsDispatchAnimatedOneDoes) {
  scene::LoadedScene s = scene::builtInScene(8);
  s.description.settings.width = 128;
  s.description.settings.height = 96;
  plan::Planner planner(test::syntheticCalibration());
  session::ScenePlayer player(context(), s, planOptions(16), frame::PointUpdatePath::Cpu, &planner);
  size_t character = player.instanceCount();
  for (size_t i = 0; i < player.instanceCount(); ++i)
    if (player.dynamicMesh(i)) character = i;
  ASSERT_LT(character, player.instanceCount()) << "the built-in scene has a skinned character";
  auto deforming = [&] {
    for (const session::MeshWork& w : player.work())
      if (w.deforms) return w;
    return session::MeshWork{};
  };
  uint64_t lastUpdates = deforming().pointUpdates, lastBounds = deforming().boundsDispatches;
  bool boundsRan = false;
  const uint32_t frames[] = {0, 1, 2, 3, 3};
  for (size_t k = 0; k < std::size(frames); ++k) {
    const uint32_t f = frames[k];
    const bool repeated = k > 0 && frames[k - 1] == f;
    const std::vector<session::ViewFrame> views = player.render(f);
    ASSERT_EQ(views[0].plans.size(), player.instanceCount());
    expectExact(player, views, f);
    const plan::Plan& p = views[0].plans[character];
    // A point update for every new frame, none for the same frame again.
    const session::MeshWork w = deforming();
    EXPECT_EQ(w.pointUpdates, lastUpdates + (repeated ? 0 : 1)) << "frame " << f;
    EXPECT_EQ(p.update.on, !repeated) << describe(views[0].plans);
    if (repeated) {
      EXPECT_FALSE(p.bounds.on);
      EXPECT_EQ(w.boundsDispatches, lastBounds) << "no bounds dispatch for a still cage";
    } else if (p.bounds.on) {
      EXPECT_GT(w.boundsDispatches, lastBounds) << "frame " << f;
      boundsRan = true;
    }
    lastUpdates = w.pointUpdates;
    lastBounds = w.boundsDispatches;
    for (const session::MeshWork& m : player.work())
      if (!m.deforms) {
        EXPECT_EQ(m.pointUpdates, 0u) << m.mesh;
        EXPECT_EQ(m.boundsDispatches, 0u) << m.mesh;
      }
    for (size_t i = 0; i < player.instanceCount(); ++i)
      if (i != character) {
        EXPECT_FALSE(views[0].plans[i].update.on) << views[0].plans[i].mesh;
        EXPECT_FALSE(views[0].plans[i].bounds.on) << views[0].plans[i].mesh;
      }
  }
  EXPECT_TRUE(boundsRan) << "the character's cone method recomputes its cull data";
}

TEST_F(ScenePlan, UndisplacedInstanceBuildsAndBindsNoDisplacementVariant) {
  OSD_CULL_REQUIRE_DATA();
  scene::LoadedScene s = sceneFromText(test::displacedScene());
  // The priors' choices (both instances cull at tess 16), not the measured ones: after the
  // exploring frames a measured rate may switch an instance off, which is not what this
  // test is about.
  plan::PlannerOptions fromPriors;
  fromPriors.exploreFrames = 0;
  plan::Planner planner(test::syntheticCalibration(), fromPriors);
  session::ScenePlayer player(context(), s, planOptions(16), frame::PointUpdatePath::Cpu, &planner);
  ASSERT_EQ(player.instanceCount(), 2u);
  for (uint32_t f = 0; f < 3; ++f) {
    const std::vector<session::ViewFrame> views = player.render(f);
    const std::vector<plan::Plan>& plans = views[0].plans;
    expectExact(player, views, f);
    EXPECT_TRUE(plans[0].displacement.on) << describe(plans);
    EXPECT_FALSE(plans[1].displacement.on) << describe(plans);
    ASSERT_TRUE(views[0].culled) << describe(plans);
    ASSERT_TRUE(plans[0].culls() && plans[1].culls()) << describe(plans);
    // The draws: only the displaced instance's patch set has a map bound.
    EXPECT_NE(player.gpuPatches(0).displacement(), nullptr);
    EXPECT_EQ(player.gpuPatches(1).displacement(), nullptr);
    // The cull kernels built: the displaced one with its displaced bound (the planned
    // kernel when occlusion runs), the undisplaced one with no displaced stage or box.
    const frame::CullPass* bumpy = player.cullFrame(0).cullPass(0);
    const frame::CullPass* twister = player.cullFrame(0).cullPass(1);
    ASSERT_NE(bumpy, nullptr);
    ASSERT_NE(twister, nullptr);
    EXPECT_TRUE(bumpy->displaced());
    EXPECT_FALSE(twister->displaced());
    for (const frame::CullMethod* m : twister->stages()) EXPECT_FALSE(m->displaced) << m->name;
    if (plans[0].occlusion.on) {
      EXPECT_EQ(plans[0].occlusion.choice, planner.options().displacedKernel);
      EXPECT_EQ(bumpy->stages().back()->name, planner.options().displacedKernel);
    }
  }
}

TEST_F(ScenePlan, FarInstanceGetsCullingOffCloseOneOnInTheSameFrame) {
  OSD_CULL_REQUIRE_DATA();
  scene::LoadedScene s = sceneFromText(nearFarScene());
  plan::PlannerOptions fromPriors;  // the choice of the priors, without exploring frames
  fromPriors.exploreFrames = 0;
  plan::Planner planner(test::syntheticCalibration(), fromPriors);
  session::ScenePlayer player(context(), s, planOptions(2), frame::PointUpdatePath::Cpu, &planner);
  const std::vector<session::ViewFrame> views = player.render(0);
  const std::vector<plan::Plan>& plans = views[0].plans;
  ASSERT_EQ(plans.size(), 2u);
  EXPECT_EQ(plans[0].box, plan::BoxInView::Crossing) << describe(plans);
  EXPECT_EQ(plans[1].box, plan::BoxInView::Inside) << describe(plans);
  EXPECT_TRUE(plans[0].culls()) << describe(plans);
  EXPECT_TRUE(plans[0].frustum.on) << describe(plans);
  EXPECT_FALSE(plans[1].culls()) << describe(plans);
  // Applied: the close instance has a cull pass, the far one none (drawn unculled).
  ASSERT_TRUE(views[0].culled);
  EXPECT_NE(player.cullFrame(0).cullPass(0), nullptr);
  EXPECT_EQ(player.cullFrame(0).cullPass(1), nullptr);
  EXPECT_GT(views[0].stats.culledFrustum, 0u);
  expectExact(player, views, 0);
}

TEST_F(ScenePlan, PlanCommandAgreesWithWhatRenderAppliesAtFrameZero) {
  OSD_CULL_REQUIRE_DATA();
  for (const bool builtIn : {true, false}) {
    scene::LoadedScene s = builtIn ? scene::builtInScene(4) : sceneFromText(test::displacedScene());
    s.description.settings.width = 160;
    s.description.settings.height = 120;
    for (const uint32_t tess : {2u, 16u}) {
      // What `osd-cull plan SCENE --frame 0 --tess T` prints ...
      plan::Planner printed(test::syntheticCalibration());
      std::vector<plan::Plan> expected;
      for (const plan::ScenePlanInput& in : plan::scenePlanInputs(s, 0, tess))
        expected.push_back(printed.plan(in.key, in.input, 0));
      // ... and what the player applies.
      plan::Planner applied(test::syntheticCalibration());
      session::ScenePlayer player(context(), s, planOptions(tess));
      player.setPlanner(&applied);
      const std::vector<session::ViewFrame> views = player.render(0);
      std::vector<plan::Plan> got;
      for (const session::ViewFrame& v : views)
        got.insert(got.end(), v.plans.begin(), v.plans.end());
      EXPECT_EQ(plan::planTable(got), plan::planTable(expected))
          << s.description.source << " tess " << tess;
      // Applied: an instance is culled by a pass exactly when its plan culls.
      for (size_t v = 0; v < views.size(); ++v) {
        if (!views[v].culled) continue;
        for (size_t i = 0; i < player.instanceCount(); ++i)
          EXPECT_EQ(player.cullFrame(v).cullPass(i) != nullptr, views[v].plans[i].culls())
              << views[v].plans[i].mesh;
      }
    }
  }
}

TEST_F(ScenePlan, RatesAreLearnedAndFramesOfAChoiceAreReused) {
  scene::LoadedScene s = scene::builtInScene(24);
  s.description.settings.width = 128;
  s.description.settings.height = 96;
  plan::PlannerOptions options;
  options.reprobeFrames = 3;  // switched-off stages run often: choices change and come back
  plan::Planner planner(test::syntheticCalibration(), options);
  session::ScenePlayer player(context(), s, planOptions(8), frame::PointUpdatePath::Cpu, &planner);
  std::set<std::string> choices;
  for (uint32_t f = 0; f < 16; ++f) {
    const std::vector<session::ViewFrame> views = player.render(f);
    std::string key;
    for (const plan::Plan& p : views[0].plans) key += p.stages.describe() + ";";
    if (views[0].culled) choices.insert(key);
    if (f % 5 == 0) expectExact(player, views, f);
  }
  // One CullFrame per distinct set of choices, reused (none for the fixed options), at most
  // the six most recently used kept.
  EXPECT_GT(choices.size(), 1u);
  EXPECT_LE(player.cullFrameCount(0), 6u);
  if (choices.size() <= 6) {
    EXPECT_EQ(player.cullFramesBuilt(0), choices.size());
  }
  // The rates were measured: a back-patch method's learned rate of an instance differs from
  // its prior.
  bool learned = false;
  for (size_t i = 0; i < player.instanceCount(); ++i)
    for (const char* m : {"tcone", "ncone", "tangent-plane"})
      learned = learned ||
                planner.rate(plan::scenePlanKey(s, 0, i), m) != planner.options().priorRates.at(m);
  EXPECT_TRUE(learned);
}

TEST_F(ScenePlan, TheFirstFrameCountsOtherBackPatchVariantsOfStaticInstancesOnly) {
  // Issue 18, scene form of Plan::countOnly: on a key's first frame every static instance runs
  // the other offered back-patch variants in counting-only passes (no occlusion, no status),
  // the planner learns their rates from them, and the frame drawn is the one without them.
  // A deforming instance is left out (its other cone methods would need bounds passes of
  // their own); no counting pass runs on the next frame.
  scene::LoadedScene s = scene::builtInScene(8);
  s.description.settings.width = 128;
  s.description.settings.height = 96;
  plan::Planner a(test::syntheticCalibration());
  plan::PlannerOptions off;
  off.countingProbes = false;
  plan::Planner b(test::syntheticCalibration(), off);
  session::ScenePlayer counting(context(), s, planOptions(4), frame::PointUpdatePath::Cpu, &a);
  session::ScenePlayer plain(context(), s, planOptions(4), frame::PointUpdatePath::Cpu, &b);
  const std::vector<session::ViewFrame> f = counting.render(0);
  const std::vector<session::ViewFrame> g = plain.render(0);
  ASSERT_EQ(f.size(), g.size());
  uint32_t expected = 0;
  bool staticCounted = false;
  for (size_t i = 0; i < counting.instanceCount(); ++i) {
    EXPECT_TRUE(g[0].plans[i].countOnly.empty());
    EXPECT_TRUE(f[0].plans[i].stages == g[0].plans[i].stages) << f[0].plans[i].mesh;
    if (counting.dynamicMesh(i)) continue;
    expected += uint32_t(f[0].plans[i].countOnly.size());
    for (const plan::StageChoice& v : f[0].plans[i].countOnly) {
      staticCounted = true;
      EXPECT_NE(
          a.rate(plan::scenePlanKey(s, 0, i), plan::RateKey::backPatch(v.backPatch, v.accuracy)),
          b.rate(plan::scenePlanKey(s, 0, i), plan::RateKey::backPatch(v.backPatch, v.accuracy)))
          << f[0].plans[i].mesh << " " << v.describe() << ": learned, not the prior";
    }
  }
  ASSERT_TRUE(staticCounted) << describe(f[0].plans);
  EXPECT_EQ(f[0].countingPasses, expected);
  EXPECT_EQ(g[0].countingPasses, 0u);
  for (size_t v = 0; v < f.size(); ++v) {
    const frame::ItemComparison c = frame::compareItems(counting.target(v).readItems(context()),
                                                        plain.target(v).readItems(context()));
    EXPECT_EQ(c.differing, 0u) << "view " << v;
  }
  const std::vector<session::ViewFrame> next = counting.render(1);
  EXPECT_EQ(next[0].countingPasses, 0u);
  EXPECT_EQ(validationLog().count(), 0u);
}

TEST(ScenePlanMemory, FlatWhileCullFramesAreBuiltAndEvictedWithoutTheLayer) {
  // Issue 18: memory flat over any scene and plan. The built-in scene's instances re-probed
  // every 3 frames visit a new set of choices nearly every frame; the player keeps the 2
  // most recent per view (setCachedFrames), so a CullFrame is built and one evicted nearly
  // every frame (3,000 frames, 2,999 built: 207.2 -> 207.8 MB, session 8; 250 here to keep
  // the test short). Without the validation layer, whose own state grows with every recorded
  // command buffer (test_mesh_session.cpp); the other tests here run validated.
  vulkan::ContextOptions options;
  options.validation = false;
  vulkan::Context context(options);
  scene::LoadedScene s = scene::builtInScene(24);
  s.description.settings.width = 48;
  s.description.settings.height = 32;
  plan::PlannerOptions po;
  po.reprobeFrames = po.maxReprobeFrames = 3;
  po.holdFrames = 1;
  plan::Planner planner(test::syntheticCalibration(), po);
  session::ScenePlayer player(context, s, planOptions(1), frame::PointUpdatePath::Cpu, &planner);
  player.setCachedFrames(2);
  EXPECT_THROW(player.setCachedFrames(0), Error);
  const uint32_t frames = s.description.settings.frameCount;
  uint64_t at100 = 0;
  for (uint32_t f = 0; f < 250; ++f) {
    player.seek(f % frames);
    player.renderCurrent(f);
    if (f == 99) at100 = test::residentKb();
  }
  const uint64_t at250 = test::residentKb();
  std::printf(
      "resident: %llu KB at frame 100, %llu KB at frame 250; %zu cull frames built, %zu kept\n",
      static_cast<unsigned long long>(at100), static_cast<unsigned long long>(at250),
      player.cullFramesBuilt(0), player.cullFrameCount(0));
  EXPECT_GT(player.cullFramesBuilt(0), 10u) << "the test evicts and rebuilds frames";
  EXPECT_LE(player.cullFrameCount(0), 2u);
  // 150 frames of a frame built and one evicted each: a frame that leaked its buffers (tens
  // of KB at least) would add several MB. The margin allows a pipeline variant first met
  // late (the choices follow measured times, so they differ under load).
  EXPECT_LT(at250, at100 + 6144);
}

TEST(ScenePlanCommand, RenderPrintsEachInstancesPlanAndItsChangesNamingInstanceAndView) {
  OSD_CULL_REQUIRE_DATA();
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  test::TempDir dir("scene_plan_");
  const fs::path calibration = dir.path() / "synthetic.txt";
  plan::storeCalibration(test::syntheticCalibration(), calibration);
  const fs::path scene = dir.write("scene.json", nearFarScene());
  const std::string base = test::osdCullProgram().string() + " render " + scene.string() +
                           " --validate --tess 2 --frames 2 --verbose --plan-calibration " +
                           calibration.string();
  const auto r = test::runCommand(base);
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  for (const char* line :
       {"plan: auto", "cull planned", "plan of instance 0 'near' in view 'main', frame 0: frustum",
        "plan of instance 1 'far' in view 'main', frame 0: ", "update off: static mesh",
        "view main frame 1:", "summary of view main: 2 frames, mean ",
        "summary of view main: plan changes "})
    EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
  // An explicit --cull or --plan off: one fixed choice for all instances, no plan.
  for (const char* fixed : {" --cull all", " --plan off"}) {
    const auto f = test::runCommand(base + fixed);
    ASSERT_EQ(f.exitCode(), 0) << f.output;
    EXPECT_NE(f.output.find("plan: off"), std::string::npos) << f.output;
    EXPECT_EQ(f.output.find("plan of instance"), std::string::npos) << f.output;
  }
}

}  // namespace
}  // namespace osd_cull
