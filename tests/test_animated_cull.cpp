// Culling a deforming mesh (frame/dynamic_patch_mesh.h, bounds_pass.h): every deformer and
// an OBJ sequence over several frames, every method against the oracle and the double
// reference of that frame, GPU bounds against the reference, and the two-pass frame's image
// against the unculled image frame after frame.
#include "adapters/obj_sequence.h"
#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/dynamic_patch_mesh.h"
#include "osd_cull/frame/verify/visibility_oracle.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/cage_animation.h"
#include "osd_cull/scene/procedural.h"
#include "support/bounds_check.h"
#include "support/temp_dir.h"
#include "support/vk_test_context.h"

#include <shared/cull_layout.h>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <memory>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

using bound::BackPatchMethod;

bound::BackPatchValidity validityOf(const CageMesh& cage) {
  return bound::backPatchValidity(summarize(*makeTopologyRefiner(cage)), bound::signedVolume(cage));
}

std::string objText(const CageMesh& cage, std::span<const glm::dvec3> positions) {
  std::string s;
  char line[128];
  for (const glm::dvec3& p : positions) {
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p.x, p.y, p.z);
    s += line;
  }
  size_t k = 0;
  for (int n : cage.faceSizes) {
    s += "f";
    for (int i = 0; i < n; ++i) s += " " + std::to_string(cage.faceVertices[k++] + 1);
    s += "\n";
  }
  return s;
}

// One animated mesh: a name, its first cage and its motion.
struct Source {
  std::string name;
  CageMesh cage;
  std::unique_ptr<scene::CageAnimation> animation;
  frame::PointUpdatePath path = frame::PointUpdatePath::Cpu;
};

std::vector<Source> sources(const test::TempDir& dir) {
  const CageMesh base = scene::defaultMesh();
  std::vector<Source> out;
  scene::DeformerParams d;
  d.amount = 0.8;
  out.push_back({"twist", base, scene::makeTwist(base.positions, d), frame::PointUpdatePath::Gpu});
  d.amount = 1.0;
  out.push_back({"bend", base, scene::makeBend(base.positions, d)});
  d.amount = 0.05;
  out.push_back({"wave", base, scene::makeWave(base.positions, d)});
  scene::SkinningParams s;
  s.swingDegrees = 35.0;
  out.push_back(
      {"skin-chain", base, scene::makeSkinning(base.positions, s), frame::PointUpdatePath::Gpu});
  s.rig = scene::SkinningRig::Limbs;
  out.push_back({"skin-limbs", base, scene::makeSkinning(base.positions, s)});
  // An OBJ sequence of three twisted key frames.
  d.amount = 0.8;
  const auto twist = scene::makeTwist(base.positions, d);
  std::vector<glm::dvec3> p(base.positions.size());
  for (int f = 0; f < 3; ++f) {
    twist->positions(0.4 * f + 0.2, p);
    dir.write("key_" + std::to_string(f) + ".obj", objText(base, p));
  }
  scene::ObjSequence seq = scene::loadObjSequence((dir.path() / "key_#.obj").string(), 2.0);
  out.push_back({"sequence", std::move(seq.firstFrame), std::move(seq.animation)});
  return out;
}

class AnimatedCullTest : public test::VkTest {};

TEST_F(AnimatedCullTest, EveryMethodHasNoFalseCullOnEveryFrameOfEveryAnimation) {
  test::TempDir dir("osd_cull_anim_");
  frame::Renderer renderer(context());
  frame::RenderTarget target(context(), 128, 128);
  frame::VisibilityOracle oracle(context());
  frame::TessellationOptions tess;
  tess.uniformLevel = 4;
  const std::vector<std::string> methods = {"tcone", "ncone", "tangent-plane", "tangent-plane-16"};
  for (Source& src : sources(dir)) {
    frame::DynamicPatchMesh mesh(context(), src.cage, {}, src.path);
    const bound::BackPatchValidity validity = validityOf(src.cage);
    ASSERT_TRUE(validity.enabled) << src.name << ": " << validity.reason;
    std::vector<std::unique_ptr<frame::CullPass>> passes;
    for (const std::string& m : methods) {
      frame::CullSettings s{true, m, "", validity};
      const BackPatchMethod ref = frame::cullMethod(m).reference;
      passes.push_back(
          ref == BackPatchMethod::TangentPlane
              ? std::make_unique<frame::CullPass>(context(), mesh.gpu(), mesh.patches(), s)
              : std::make_unique<frame::CullPass>(context(), mesh.gpu(), mesh.patches(), s,
                                                  mesh.cullData(ref)));
    }
    std::vector<uint64_t> culled(methods.size(), 0);
    uint64_t patchViews = 0;
    const frame::Bounds bounds = frame::boundsOf(mesh.patches().points);
    for (int f = 0; f < 3; ++f) {
      const double t = src.animation->duration() * (0.15 + 0.3 * f);
      std::vector<glm::dvec3> positions(src.animation->vertexCount());
      src.animation->positions(t, positions);
      mesh.setCagePositions(positions);
      ASSERT_TRUE(mesh.update());
      const PatchSet& host = mesh.patches();
      const frame::Camera camera =
          frame::orbit(frame::frameBounds(bounds, {0.4, 0.5, 1.0}, {0, 1, 0}, 40.0, 128, 128),
                       bounds.center(), {0, 1, 0}, 110.0 * f);
      const frame::VisibilityCounts counts =
          oracle.query(renderer, target, camera, mesh.gpu(), &host, {}, tess);
      const bound::CullView view = bound::makeCullView(camera.viewProjection());
      for (size_t m = 0; m < methods.size(); ++m) {
        const BackPatchMethod ref = frame::cullMethod(methods[m]).reference;
        if (ref != BackPatchMethod::TangentPlane) {
          const test::BoundsCheck c =
              test::checkBounds(host, ref, mesh.boundsPass(ref)->readBounds(context()));
          EXPECT_EQ(c.violations, 0u) << src.name << " frame " << f << " " << methods[m];
        }
        passes[m]->run(camera, tess);
        const auto results = passes[m]->results();
        std::vector<bound::TriangleShape> shapes;
        const auto codes =
            bound::referenceCull(host, view, passes[m]->referenceTests(camera, tess, shapes),
                                 bound::buildPatchCones(host, ref));
        uint32_t falseCulls = 0, notInReference = 0;
        for (uint32_t p = 0; p < host.patchCount(); ++p) {
          const bound::CullCode g{results[p]};
          if (!g.culled()) continue;
          ++culled[m];
          falseCulls += counts.visible(p);
          notInReference += !bound::CullCode{codes[p]}.culled();
        }
        EXPECT_EQ(falseCulls, 0u) << src.name << " frame " << f << " " << methods[m];
        EXPECT_EQ(notInReference, 0u) << src.name << " frame " << f << " " << methods[m];
      }
      patchViews += host.patchCount();
    }
    for (size_t m = 0; m < methods.size(); ++m)
      EXPECT_GT(culled[m], patchViews / 10) << src.name << " " << methods[m] << " culls little";
  }
}

TEST_F(AnimatedCullTest, TwoPassFramesOfASkinnedMeshEqualTheUnculledImage) {
  const CageMesh cage = scene::defaultMesh();
  scene::SkinningParams s;
  s.rig = scene::SkinningRig::Limbs;
  s.swingDegrees = 40.0;
  s.frequency = 1.0;
  const auto skin = scene::makeSkinning(cage.positions, s);
  for (frame::PointUpdatePath path : {frame::PointUpdatePath::Cpu, frame::PointUpdatePath::Gpu}) {
    frame::DynamicPatchMesh mesh(context(), cage, {}, path);
    frame::Renderer renderer(context());
    frame::RenderTarget target(context(), 160, 120), reference(context(), 160, 120);
    frame::RenderTarget items(context(), 160, 120);
    frame::VisibilityOracle oracle(context());
    frame::CullFrameOptions o;
    o.render.tessellation.uniformLevel = 4;
    o.cull = {true, "tcone", "hiz", validityOf(cage)};
    const frame::CullMesh meshes[] = {{.gpu = &mesh.gpu(),
                                       .host = &mesh.patches(),
                                       .cullData = &mesh.cullData(BackPatchMethod::TCone)}};
    frame::CullFrame cull(context(), renderer, target, meshes, o);
    const frame::Bounds bounds = frame::boundsOf(mesh.patches().points);
    const frame::Camera camera =
        frame::frameBounds(bounds, {0.3, 0.4, 1.0}, {0, 1, 0}, 40.0, 160, 120);
    uint64_t culledTotal = 0, occlusionTotal = 0;
    std::vector<glm::dvec3> positions(cage.positions.size());
    for (int f = 0; f < 8; ++f) {
      skin->positions(f / 8.0, positions);  // a fast swing: 45° of phase per frame
      mesh.setCagePositions(positions);
      mesh.update();
      const frame::CullFrameStats stats = cull.render(camera, {});
      culledTotal += stats.culled();
      // Every patch the frame culled (any stage, Hi-Z included) has no pixel in this frame's
      // oracle.
      const frame::VisibilityCounts counts = oracle.query(
          renderer, items, camera, mesh.gpu(), &mesh.patches(), {}, o.render.tessellation);
      const std::vector<uint32_t> results = cull.readResults(0);
      uint32_t falseCulls = 0, culledOcclusion = 0;
      for (uint32_t p = 0; p < results.size(); ++p) {
        const bound::CullCode code{results[p]};
        falseCulls += code.culled() && counts.visible(p);
        culledOcclusion += code.culled() && code.stage() == shader::kStageOcclusion;
      }
      EXPECT_EQ(falseCulls, 0u) << toString(path) << " frame " << f;
      occlusionTotal += culledOcclusion;
      const frame::PatchDraw draw{&mesh.gpu(), &mesh.patches(), 0};
      renderer.render(reference, camera, {&draw, 1}, {}, o.render);
      const auto a = target.readItems(context()), b = reference.readItems(context());
      const auto ca = target.readColor(context()), cb = reference.readColor(context());
      uint32_t lost = 0, differ = 0;
      for (size_t i = 0; i < a.size(); ++i) {
        lost += b[i] != 0 && a[i] == 0;
        bool d = a[i] != b[i];
        for (int c = 0; c < 4; ++c) d = d || ca[4 * i + c] != cb[4 * i + c];
        differ += d;
      }
      EXPECT_EQ(lost, 0u) << toString(path) << " frame " << f;
      EXPECT_LE(differ, a.size() / 10000) << toString(path) << " frame " << f;
    }
    EXPECT_GT(culledTotal, 8u * mesh.patches().patchCount() / 10) << toString(path);
    EXPECT_GT(occlusionTotal, 0u) << toString(path) << ": Hi-Z culled nothing";
  }
}

}  // namespace
}  // namespace osd_cull
