// The displaced kernels on the GPU (shaders/cull/displaced_bound.glsl): zero false culls
// against the item-buffer oracle of the displaced draw and every GPU cull a cull of the
// double reference (bound/displaced_bounds.h), for all six kernels, on a creased shape
// with boundaries, BigGuy and extreme maps.
#include "adapters/load_mesh.h"
#include "osd_cull/bound/displaced_map.h"
#include "osd_cull/frame/camera.h"
#include "osd_cull/frame/verify/cull_verification.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "support/cull_test_meshes.h"
#include "support/displacement_test_maps.h"
#include "support/test_data.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>

namespace osd_cull {
namespace {

class DisplacedCullTest : public test::VkTest {};

const std::vector<std::string> kKernels = {"frustum",  "full-oobb", "acon-oobb", "con-oobb",
                                           "full-caf", "acon-caf",  "con-caf"};

// Runs every kernel over `views` random views (whole-object and sphere) and checks them.
std::vector<frame::MethodTotals> verifyDisplaced(vulkan::Context& context,
                                                 const PatchExtraction& ex,
                                                 const bound::DisplacementMap& map, uint32_t views,
                                                 frame::ViewSet set, const std::string& what) {
  frame::VerifyOptions options;
  options.tessellation.uniformLevel = 4;
  options.displacementMap = &map;
  options.uvCorners = ex.uvCorners;
  frame::CullVerifier verifier(context, ex.patches, kKernels, {false, "not tested"}, options);
  frame::ViewSetOptions viewOptions;
  viewOptions.set = set;
  viewOptions.count = views;
  viewOptions.width = 64;
  viewOptions.height = 64;
  for (const frame::Camera& camera :
       frame::randomViews(frame::boundsOf(ex.patches.points), viewOptions))
    verifier.verifyView(camera);
  test::expectNoViolations(verifier, what);
  EXPECT_EQ(verifier.totals().size(), kKernels.size()) << what;
  return verifier.totals();
}

uint64_t culledBy(const std::vector<frame::MethodTotals>& totals, const std::string& name) {
  for (const frame::MethodTotals& t : totals)
    if (t.name == name) return t.culled;
  ADD_FAILURE() << "no totals for " << name;
  return 0;
}

// Table 1's order on the views run: Full <= ACoN <= CoN per box, OOBB <= CAF per extension.
void expectTable1Order(const std::vector<frame::MethodTotals>& v, const std::string& what) {
  for (const std::string box : {"oobb", "caf"}) {
    EXPECT_LE(culledBy(v, "full-" + box), culledBy(v, "acon-" + box)) << what << " " << box;
    EXPECT_LE(culledBy(v, "acon-" + box), culledBy(v, "con-" + box)) << what << " " << box;
  }
  for (const std::string e : {"full", "acon", "con"})
    EXPECT_LE(culledBy(v, e + "-oobb"), culledBy(v, e + "-caf")) << what << " " << e;
}

bound::DisplacementMap procedural(double scale) {
  return {"procedural", 128, 128, scene::proceduralDisplacementTexels(128, 4), scale, 0.5};
}

TEST_F(DisplacedCullTest, NoFalseCullsOnACreasedShapeWithBoundaries) {
  OSD_CULL_REQUIRE_DATA();
  const PatchExtraction ex =
      extractPatches(adapters::loadCage(test::dataDir() / "shapes/catmark_single_crease.obj"));
  const auto map = procedural(0.15 * frame::boundsOf(ex.patches.points).radius());
  const auto v = verifyDisplaced(context(), ex, map, 12, frame::ViewSet::Sphere, "single_crease");
  EXPECT_GT(culledBy(v, "con-caf"), 0u);
  expectTable1Order(v, "single_crease");
}

TEST_F(DisplacedCullTest, NoFalseCullsOnDisplacedBigGuy) {
  OSD_CULL_REQUIRE_DATA();
  PatchOptions options;
  options.isolationLevel = 1;
  const PatchExtraction ex =
      extractPatches(adapters::loadCage(test::dataDir() / "characters/bigguy.obj"), options);
  const auto map = procedural(1.5);
  const auto v = verifyDisplaced(context(), ex, map, 4, frame::ViewSet::WholeObject, "bigguy");
  for (const char* k : {"full-oobb", "acon-caf", "con-caf"}) EXPECT_GT(culledBy(v, k), 0u) << k;
  expectTable1Order(v, "bigguy");
}

TEST_F(DisplacedCullTest, NoFalseCullsWithExtremeMaps) {
  OSD_CULL_REQUIRE_DATA();
  const PatchExtraction ex =
      extractPatches(adapters::loadCage(test::dataDir() / "shapes/catmark_cube.obj"));
  const auto maps = test::extremeDisplacementMaps(0.4);
  for (const auto& map : maps) {
    const auto v = verifyDisplaced(context(), ex, map, 3, frame::ViewSet::Sphere, map.name());
    expectTable1Order(v, map.name());
  }
}

}  // namespace
}  // namespace osd_cull
