// session::ScenePlayer: every view of a scene (a main camera on a path and a shadow-map view,
// a spinning, sliding instance, a mirrored one and the skinned character)
// keeps its own status over the shared meshes, and each frame's culled image equals the same
// frame drawn without culling (0 pixels lost, < 0.01% differing).
#include "adapters/scene_assets.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/session/scene_player.h"
#include "support/test_data.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace osd_cull {
namespace {

class ScenePlayerTest : public test::VkTest {
 protected:
  void playAndCompare(const std::string& backPatchMethod);
};

void ScenePlayerTest::playAndCompare(const std::string& backPatchMethod) {
  scene::LoadedScene s = scene::builtInScene(12);
  s.description.settings.width = 128;
  s.description.settings.height = 96;
  scene::ViewDescription sun;
  sun.name = "sun";
  sun.kind = scene::ViewDescription::Kind::Shadow;
  sun.lightDirection = {-0.4, 0.5, -1.0};
  sun.width = sun.height = 96;
  s.description.views.push_back(sun);
  // A mirrored copy of the creased cube shares its points.
  scene::InstanceDescription mirror = s.description.instances[3];
  mirror.name = "mirrored cube";
  mirror.transform = scene::composeTransform({1.0, -1.6, -0.4}, {0, 0, 30}, {-0.6, 0.6, 0.6});
  s.description.instances.push_back(mirror);
  // The torus spins and slides: instance motion, re-tested every frame from its status.
  s.description.instances[1].motion.spinAxis = {0.3, 0.0, 1.0};
  s.description.instances[1].motion.spinDegreesPerSecond = 90.0;
  s.description.instances[1].motion.keys = {{0.0, {0.0, 0.0, 0.0}}, {0.5, {-0.8, -0.6, 0.0}}};

  frame::CullFrameOptions options;
  options.render.tessellation.uniformLevel = 3;
  options.render.cullBackFaces = true;
  options.cull.backPatch = backPatchMethod;
  session::ScenePlayer player(context(), s, options);
  // The skinned character (instance 4) is back-patch culled with the cull data the GPU
  // bounds pass recomputes every frame, for every back-patch method.
  ASSERT_NE(player.cullFrame(0).cullPass(4), nullptr);
  EXPECT_TRUE(player.cullFrame(0).cullPass(4)->backPatchEnabled())
      << player.cullFrame(0).cullPass(4)->backPatchNote();
  ASSERT_EQ(player.viewCount(), 2u);
  ASSERT_EQ(player.instanceCount(), 6u);
  EXPECT_EQ(player.describe().size(), 5u);  // five meshes: the mirror shares the cube's points
  frame::RenderTarget plain96(context(), 96, 96), plain128(context(), 128, 96);
  uint32_t culled[2] = {0, 0};
  for (uint32_t f = 0; f < 12; f += 3) {
    const std::vector<session::ViewFrame> views = player.render(f);
    ASSERT_EQ(views.size(), 2u);
    for (size_t v = 0; v < 2; ++v) {
      culled[v] += views[v].stats.culled();
      frame::RenderTarget& plain = v == 0 ? plain128 : plain96;
      const frame::ItemComparison c = player.compareWithUnculled(v, plain).items;
      const uint64_t covered = c.covered, differing = c.differing;
      EXPECT_GT(covered, c.pixels / 4) << views[v].view << " frame " << f;
      EXPECT_EQ(c.lost, 0u) << views[v].view << " frame " << f;
      EXPECT_EQ(differing, 0u) << views[v].view << " frame " << f;
      std::printf("%s frame %u: culled %u of %u, %llu pixels covered, %llu differing\n",
                  views[v].view.c_str(), f, views[v].stats.culled(), views[v].stats.patchesTotal,
                  static_cast<unsigned long long>(covered),
                  static_cast<unsigned long long>(differing));
    }
  }
  EXPECT_GT(culled[0], 0u);
  EXPECT_GT(culled[1], 0u);
  // Each view has its own status: the sun sees the tops, the main camera the fronts.
  const auto mainStatus = player.cullFrame(0).visibility(0).readStatus(context());
  const auto sunStatus = player.cullFrame(1).visibility(0).readStatus(context());
  EXPECT_NE(mainStatus, sunStatus);
}

TEST_F(ScenePlayerTest, EveryViewDrawsTheUnculledImageWithItsOwnStatus) {
  playAndCompare("tangent-plane");
}

TEST_F(ScenePlayerTest, SkinnedCharacterWithPerFrameConesDrawsTheUnculledImage) {
  playAndCompare("ncone");
}

// Issue 10: a static mesh is never re-evaluated; a deforming one recomputes its points and
// its bounds-pass cones once per frame it moves, and not again when the frame is replayed.
TEST_F(ScenePlayerTest, OnlyDeformingMeshesUpdateAndOnlyOnFramesTheyMove) {
  scene::LoadedScene s = scene::builtInScene(6);
  s.description.settings.width = 64;
  s.description.settings.height = 48;
  frame::CullFrameOptions options;
  options.render.tessellation.uniformLevel = 2;
  options.cull.backPatch = "tcone";
  for (const frame::PointUpdatePath path :
       {frame::PointUpdatePath::Cpu, frame::PointUpdatePath::Gpu}) {
    session::ScenePlayer player(context(), s, options, path);
    const auto before = player.work();
    ASSERT_EQ(before.size(), 5u);
    for (uint32_t f : {0u, 1u, 1u, 2u, 2u, 3u}) player.render(f);
    const auto after = player.work();
    size_t deforming = 0;
    for (size_t m = 0; m < after.size(); ++m) {
      SCOPED_TRACE(after[m].mesh + " " + frame::toString(path));
      if (!after[m].deforms) {
        EXPECT_EQ(after[m].pointUpdates, 0u);
        EXPECT_EQ(after[m].boundsDispatches, 0u);
        continue;
      }
      ++deforming;
      // Frames 0, 1, 2, 3: four poses; the replays of 1 and 2 run nothing.
      EXPECT_EQ(after[m].pointUpdates - before[m].pointUpdates, 4u);
      // One cone method in use (tcone): one bounds dispatch per pose.
      EXPECT_EQ(after[m].boundsDispatches - before[m].boundsDispatches, 4u);
    }
    EXPECT_EQ(deforming, 1u);  // the skinned character
    for (size_t i = 0; i < player.instanceCount(); ++i)
      EXPECT_EQ(player.dynamicMesh(i) != nullptr,
                s.meshes[s.description.instances[i].mesh].animation != nullptr);
  }
}

// Issue 11 on moving meshes in scenes: a twisting, displaced mesh and its mirror image are
// culled with the displaced bound whose cones the GPU bounds pass recomputes every frame,
// and every frame draws what the unculled frame draws.
TEST_F(ScenePlayerTest, DeformingDisplacedMeshDrawsTheUnculledImage) {
  OSD_CULL_REQUIRE_DATA();
  scene::SceneDescription d;
  d.source = "test: deforming displaced mesh";
  scene::MeshDescription mesh;
  mesh.name = "bumpy";
  mesh.file = (test::dataDir() / "shapes/catmark_single_crease.obj").string();
  mesh.patches.isolationLevel = 1;
  mesh.animation.kind = scene::AnimationSource::Kind::Twist;
  mesh.animation.deformer = {.axis = 2, .amount = 0.6, .frequency = 0.5};
  mesh.displacement = scene::DisplacementDescription{.source = "procedural", .scale = 0.3};
  d.meshes.push_back(mesh);
  scene::InstanceDescription bumpy{.name = "bumpy", .mesh = 0};
  d.instances.push_back(bumpy);
  bumpy.name = "mirror";
  bumpy.transform = scene::composeTransform({2.5, 0, 0}, {0, 0, 30}, {-1, 1, 1});
  d.instances.push_back(bumpy);
  scene::ViewDescription view;
  view.name = "main";
  view.eye = {1.2, -6, 3};
  view.target = {1.2, 0, 0};
  view.orbitDegreesPerSecond = 90;
  d.views.push_back(view);
  d.settings.width = 96;
  d.settings.height = 72;
  d.settings.framesPerSecond = 4;
  scene::LoadedScene s = adapters::loadScene(d);

  frame::CullFrameOptions options;
  options.render.tessellation.uniformLevel = 3;
  options.cull.backPatch = "ncone";  // off for displaced meshes: the note says why
  session::ScenePlayer player(context(), s, options);
  const frame::CullPass* pass = player.cullFrame(0).cullPass(0);
  ASSERT_NE(pass, nullptr);
  EXPECT_TRUE(pass->displaced());
  EXPECT_FALSE(pass->backPatchEnabled());
  EXPECT_EQ(pass->instanceCount(), 2u);  // both instances in one dispatch
  ASSERT_NE(player.dynamicMesh(0), nullptr);
  frame::RenderTarget plain(context(), 96, 72);
  uint32_t culled = 0;
  for (uint32_t f = 0; f < 6; ++f) {
    culled += player.render(f)[0].stats.culled();
    const frame::ItemComparison c = player.compareWithUnculled(0, plain).items;
    EXPECT_GT(c.covered, c.pixels / 20) << "frame " << f;
    EXPECT_EQ(c.lost, 0u) << "frame " << f;
    EXPECT_EQ(c.differing, 0u) << "frame " << f;
  }
  EXPECT_GT(culled, 0u);
  const frame::BoundsPass* bounds =
      player.dynamicMesh(0)->displacedBoundsPass(bound::DisplacedExtension::ACoN);
  ASSERT_NE(bounds, nullptr);
  EXPECT_GE(bounds->dispatchCount(), 6u);  // recomputed on every frame the mesh moved
}

}  // namespace
}  // namespace osd_cull
