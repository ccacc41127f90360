// Culling a deforming mesh (frame/dynamic_patch_mesh.h, bounds_pass.h): every deformer and
// an OBJ sequence over several frames, every back-patch method (the tangent planes with 1
// and 16 threads included) reading the bounds pass's data of that frame, against the oracle
// and the double reference of that frame, GPU bounds against the reference; the six
// displaced kernels on a deforming displaced mesh the same way; and the two-pass frame's
// image against the unculled image frame after frame.
#include "adapters/obj_sequence.h"
#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/cull/cull_pass_displaced.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/dynamic_patch_mesh.h"
#include "osd_cull/frame/hiz/hiz_cull_stage.h"
#include "osd_cull/frame/hiz/hiz_pyramid.h"
#include "osd_cull/frame/verify/cull_verification.h"
#include "osd_cull/frame/verify/visibility_oracle.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/cage_animation.h"
#include "osd_cull/scene/procedural.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "osd_cull/vk/transfer.h"
#include "support/bounds_check.h"
#include "support/displacement_test_maps.h"
#include "support/temp_dir.h"
#include "support/vk_test_context.h"

#include <shared/cull_layout.h>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cstdio>
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
  frame::RenderTarget target(context(), 96, 96);
  frame::VisibilityOracle oracle(context());
  frame::TessellationOptions tess;
  tess.uniformLevel = 4;
  // The last entry: the tangent plane exact for the surface only (drawn-triangle bound
  // off), whose Gregory patches are culled by the Gregory TCONE of the frame (with the bound
  // on they never are): checked against the reference only, as the surface-exact tests
  // may lose single silhouette pixels of the drawn triangles.
  const std::vector<std::string> methods = {"tcone", "ncone", "tangent-plane", "tangent-plane-16",
                                            "tangent-plane"};
  const size_t surfaceOnly = methods.size() - 1;
  constexpr int kFrames = 6;
  for (Source& src : sources(dir)) {
    frame::DynamicPatchMesh mesh(context(), src.cage, {}, src.path);
    const bound::BackPatchValidity validity = validityOf(src.cage);
    ASSERT_TRUE(validity.enabled) << src.name << ": " << validity.reason;
    // Every method reads the bounds pass's data of the frame (the tangent planes: the
    // Gregory TCONE; their Bézier test reads the points).
    std::vector<std::unique_ptr<frame::CullPass>> passes;
    for (const std::string& m : methods) {
      frame::CullSettings s{true, m, "", validity};
      s.drawnTriangles = passes.size() != surfaceOnly;
      passes.push_back(std::make_unique<frame::CullPass>(
          context(), mesh.gpu(), mesh.patches(), s, mesh.cullData(frame::cullMethod(m).reference)));
    }
    std::vector<uint64_t> culled(methods.size(), 0);
    uint64_t patchViews = 0, culledGregory = 0;
    const frame::Bounds bounds = frame::boundsOf(mesh.patches().points);
    for (int f = 0; f < kFrames; ++f) {
      const double t = src.animation->duration() * (0.1 + 0.8 * f / (kFrames - 1));
      std::vector<glm::dvec3> positions(src.animation->vertexCount());
      src.animation->positions(t, positions);
      mesh.setCagePositions(positions);
      ASSERT_TRUE(mesh.update());
      const PatchSet& host = mesh.patches();
      const frame::Camera camera =
          frame::orbit(frame::frameBounds(bounds, {0.4, 0.5, 1.0}, {0, 1, 0}, 40.0, 96, 96),
                       bounds.center(), {0, 1, 0}, 110.0 * f);
      const frame::VisibilityCounts counts =
          oracle.query(renderer, target, camera, mesh.gpu(), &host, {}, tess);
      const bound::CullView view = bound::makeCullView(camera.viewProjection());
      // The bounds of each method's pass (the tangent-plane kernels share one).
      for (BackPatchMethod ref :
           {BackPatchMethod::TCone, BackPatchMethod::NCone, BackPatchMethod::TangentPlane}) {
        const test::BoundsCheck c =
            test::checkBounds(host, ref, mesh.boundsPass(ref)->readBounds(context()));
        EXPECT_EQ(c.violations, 0u) << src.name << " frame " << f << " " << toString(ref);
      }
      for (size_t m = 0; m < methods.size(); ++m) {
        const BackPatchMethod ref = frame::cullMethod(methods[m]).reference;
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
          culledGregory += m == surfaceOnly && g.stage() == shader::kStageBackPatch &&
                           host.type(p) == PatchType::Gregory;
        }
        if (m != surfaceOnly) {
          EXPECT_EQ(falseCulls, 0u) << src.name << " frame " << f << " " << methods[m];
        }
        EXPECT_EQ(notInReference, 0u) << src.name << " frame " << f << " " << methods[m];
      }
      patchViews += host.patchCount();
    }
    for (size_t m = 0; m < methods.size(); ++m)
      EXPECT_GT(culled[m], patchViews / 10) << src.name << " " << methods[m] << " culls little";
    EXPECT_GT(culledGregory, 0u) << src.name << ": no Gregory patch culled by its TCONE";
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

// The default mesh with planar UVs, deformable on the GPU, and the procedural map at 8% of
// its bounding radius.
struct DisplacedDefaultMesh {
  explicit DisplacedDefaultMesh(vulkan::Context& context)
      : cage(test::withPlanarUVs(scene::defaultMesh())),
        extraction(extractPatches(cage)),
        uvCorners(extraction.uvCorners),
        mesh(std::make_unique<frame::DynamicPatchMesh>(context, std::move(extraction),
                                                       cage.positions)),
        rest(frame::boundsOf(mesh->patches().points)),
        map("procedural", 128, 128, scene::proceduralDisplacementTexels(128, 4),
            0.08 * rest.radius(), 0.5) {}
  CageMesh cage;
  PatchExtraction extraction;  // moved into mesh
  std::vector<glm::dvec2> uvCorners;
  std::unique_ptr<frame::DynamicPatchMesh> mesh;
  frame::Bounds rest;
  bound::DisplacementMap map;
};

// Issue 11 on a deforming mesh: the default mesh with planar UVs, the procedural
// displacement and a twist, every frame culled by each of the six displaced kernels (Hi-Z
// occlusion with the displaced bound, after the displaced frustum test) reading the cones
// the bounds pass recomputed for that frame. Each frame: the GPU data bounds the double
// reference, no culled patch has a pixel in the oracle of the displaced draw, and every GPU
// cull is a cull of the double-precision kernel reference run with the same cones.
TEST_F(AnimatedCullTest, DisplacedKernelsHaveNoFalseCullOnEveryFrameOfADeformingMesh) {
  const DisplacedDefaultMesh displaced(context());
  const CageMesh& cage = displaced.cage;
  const std::vector<glm::dvec2>& uvCorners = displaced.uvCorners;
  frame::DynamicPatchMesh& mesh = *displaced.mesh;
  const frame::Bounds rest = displaced.rest;
  const bound::DisplacementMap& map = displaced.map;
  frame::GpuDisplacement displacement(context(), map, uvCorners, mesh.patches().patchCount());
  mesh.gpu().setDisplacement(&displacement);
  const std::vector<bound::DisplacementRange> ranges =
      bound::displacementRanges(mesh.patches(), uvCorners, map);

  frame::Renderer renderer(context());
  frame::RenderTarget target(context(), 96, 96);
  frame::VisibilityOracle oracle(context());
  const frame::HiZOptions hizOptions;
  frame::HiZPyramid pyramid(context(), target.depth(), hizOptions);
  frame::HiZCullStage stage(context(), pyramid);
  frame::TessellationOptions tess;
  tess.uniformLevel = 4;
  struct Kernel {
    std::string name;
    bound::DisplacedExtension extension;
    std::unique_ptr<frame::CullPass> pass;
    uint64_t culled = 0;
  };
  std::vector<Kernel> kernels;
  for (const frame::CullMethod& m : frame::cullMethods()) {
    if (!m.displaced) continue;
    frame::CullSettings s{true, "", m.name, {false, "displaced"}};
    s.displacementMap = &map;
    s.uvCorners = uvCorners;
    const bound::DisplacedExtension e = m.displaced->extension;
    kernels.push_back({m.name, e,
                       std::make_unique<frame::CullPass>(context(), mesh.gpu(), mesh.patches(), s,
                                                         mesh.displacedCullData(map, uvCorners, e)),
                       0});
  }
  ASSERT_EQ(kernels.size(), 6u);
  scene::DeformerParams d;
  d.amount = 0.8;
  const auto twist = scene::makeTwist(cage.positions, d);
  std::vector<glm::dvec3> positions(cage.positions.size());
  constexpr int kFrames = 5;
  uint64_t patchViews = 0;
  for (int f = 0; f < kFrames; ++f) {
    twist->positions(twist->duration() * f / (kFrames - 1), positions);
    mesh.setCagePositions(positions);
    ASSERT_TRUE(mesh.update());
    const PatchSet& host = mesh.patches();
    // Close views (part of the mesh outside) and whole views, around the mesh.
    for (int v = 0; v < 2; ++v) {
      const frame::Camera camera = frame::orbit(
          frame::frameBounds(rest, {0.4, 0.5, 1.0}, {0, 1, 0}, v == 0 ? 25.0 : 45.0, 96, 96),
          rest.center(), {0, 1, 0}, 70.0 * f + 150.0 * v);
      const frame::VisibilityCounts counts =
          oracle.query(renderer, target, camera, mesh.gpu(), &host, {}, tess);
      pyramid.build(context(), frame::RenderTarget::kDepthLayout);
      const bound::HiZPyramid hizReference = bound::buildHiZPyramid(
          target.readDepth(context()), camera.width, camera.height, hizOptions.fullResolution);
      for (Kernel& k : kernels) {
        const std::string what =
            k.name + " frame " + std::to_string(f) + " view " + std::to_string(v);
        const frame::BoundsPass& bp = *mesh.displacedBoundsPass(k.extension);
        std::vector<bound::DisplacedPatch> data = bp.readDisplaced(context());
        const test::BoundsCheck c = test::checkDisplacedBounds(host, k.extension, ranges, data);
        EXPECT_EQ(c.violations, 0u) << what;
        for (const std::string& m : c.firstViolations) ADD_FAILURE() << what << ": " << m;
        for (size_t p = 0; p < data.size(); ++p) data[p].range = ranges[p];  // exact D range
        k.pass->run(camera, tess, stage.set());
        const auto results = k.pass->results();
        const auto codes = frame::displacedReferenceCull(host, *k.pass, data, camera, &hizReference,
                                                         hizOptions.lookup);
        uint32_t falseCulls = 0, notInReference = 0;
        for (uint32_t p = 0; p < host.patchCount(); ++p) {
          if (!bound::CullCode{results[p]}.culled()) continue;
          ++k.culled;
          falseCulls += counts.visible(p);
          notInReference += !bound::CullCode{codes[p]}.culled();
        }
        EXPECT_EQ(falseCulls, 0u) << what;
        EXPECT_EQ(notInReference, 0u) << what;
      }
      patchViews += host.patchCount();
    }
  }
  // Each extension once when first asked for, then ACoN and CoN each frame (Full: no cone).
  EXPECT_EQ(mesh.counters().boundsDispatches, 3u + 2u * kFrames);
  for (const Kernel& k : kernels) {
    EXPECT_GT(k.culled, patchViews / 20) << k.name << " culls little";
    std::printf("%s: %.1f%% culled over %d frames\n", k.name.c_str(),
                100.0 * double(k.culled) / double(patchViews), kFrames);
  }
}

// `osd-cull verify SCENE` on a deforming displaced instance (scene_verify.cpp) hands the
// verifier the cones the GPU bounds pass computed for the frame
// (VerifyOptions::displacedCullData), as ScenePlayer culls with them. With them: no false
// cull, every GPU cull a cull of the double reference (run on that data with the exact D
// range). With the same buffer but Dmin = Dmax = 0 (a bound that ignores the displacement)
// the verifier must see the kernel cull displaced-visible patches: it really culls with the
// data it was given, and the oracle and the reference catch bad data.
TEST_F(AnimatedCullTest, VerifierCullsADeformingDisplacedMeshWithItsGpuBoundsPassData) {
  const DisplacedDefaultMesh displaced(context());
  frame::DynamicPatchMesh& mesh = *displaced.mesh;
  scene::DeformerParams d;
  d.amount = 0.8;
  const auto twist = scene::makeTwist(displaced.cage.positions, d);
  std::vector<glm::dvec3> positions(displaced.cage.positions.size());
  twist->positions(twist->duration() * 0.7, positions);
  mesh.setCagePositions(positions);
  ASSERT_TRUE(mesh.update());
  const vulkan::Buffer& gpuData =
      mesh.displacedCullData(displaced.map, displaced.uvCorners, bound::DisplacedExtension::CoN);
  // The same data with Dmin = Dmax = 0 in every patch's first vec4.
  std::vector<float> flat = vulkan::readback<float>(context(), gpuData);
  for (size_t p = 0; p < mesh.patches().patchCount(); ++p)
    flat[4 * shader::kConeVec4s * p] = flat[4 * shader::kConeVec4s * p + 1] = 0.0f;
  vulkan::Buffer flatData(context(), flat.size() * sizeof(float),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::upload<float>(context(), flatData, flat);

  std::vector<frame::Camera> cameras;
  for (int v = 0; v < 6; ++v)
    cameras.push_back(frame::orbit(
        frame::frameBounds(displaced.rest, {0.4, 0.5, 1.0}, {0, 1, 0}, v % 2 ? 25.0 : 45.0, 96, 96),
        displaced.rest.center(), {0, 1, 0}, 60.0 * v));
  frame::MethodTotals totals[2];
  for (int k = 0; k < 2; ++k) {
    frame::VerifyOptions options;
    options.tessellation.uniformLevel = 4;
    options.displacementMap = &displaced.map;
    options.uvCorners = displaced.uvCorners;
    options.displacedCullData[bound::DisplacedExtension::CoN] = k == 0 ? &gpuData : &flatData;
    frame::CullVerifier verifier(context(), mesh.patches(), {"con-caf"}, {false, "displaced"},
                                 options);
    for (const frame::Camera& camera : cameras) verifier.verifyView(camera);
    ASSERT_EQ(verifier.totals().size(), 1u);
    totals[k] = verifier.totals()[0];
  }
  std::printf(
      "GPU bounds data: %llu culled, %llu false; flat data: %llu culled, %llu false, "
      "%llu not in the reference\n",
      static_cast<unsigned long long>(totals[0].culled),
      static_cast<unsigned long long>(totals[0].falseCulls),
      static_cast<unsigned long long>(totals[1].culled),
      static_cast<unsigned long long>(totals[1].falseCulls),
      static_cast<unsigned long long>(totals[1].notInReference));
  EXPECT_EQ(totals[0].falseCulls, 0u);
  EXPECT_EQ(totals[0].notInReference, 0u);
  EXPECT_GT(totals[0].culled, totals[0].patchViews / 20);
  EXPECT_GT(totals[1].culled, totals[0].culled);
  EXPECT_GT(totals[1].notInReference, 0u);
}

}  // namespace
}  // namespace osd_cull
