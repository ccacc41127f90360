// When back-patch culling may be used on a mesh (closed, manifold, oriented outward), and
// the orientation convention N = Bu x Bv checked against OpenSubdiv's own patches.
#include "osd_cull/bound/back_patch_validity.h"
#include "support/test_data.h"
#include "test_bound_fixtures.h"
#include "test_patch_support.h"

#include <gtest/gtest.h>

#include <string>

namespace osd_cull::bound {
namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

CageMesh reversed(CageMesh m) {
  size_t first = 0;
  for (int n : m.faceSizes) {
    std::reverse(m.faceVertices.begin() + static_cast<long>(first),
                 m.faceVertices.begin() + static_cast<long>(first) + n);
    first += static_cast<size_t>(n);
  }
  return m;
}

BackPatchValidity decide(const CageMesh& m) {
  return backPatchValidity(summarize(*makeTopologyRefiner(m)), signedVolume(m));
}

TEST(BoundValidity, ClosedOutwardCubeEnablesBackPatchCulling) {
  const CageMesh cube = scene::cube();
  EXPECT_DOUBLE_EQ(signedVolume(cube), 8.0);
  const BackPatchValidity v = decide(cube);
  EXPECT_TRUE(v.enabled) << v.reason;
  // Without a volume the topology alone enables it and says what was assumed.
  const BackPatchValidity assumed = backPatchValidity(summarize(*makeTopologyRefiner(cube)));
  EXPECT_TRUE(assumed.enabled);
  EXPECT_TRUE(contains(assumed.reason, "assumed")) << assumed.reason;
}

TEST(BoundValidity, InwardOrientedCubeIsDisabled) {
  const CageMesh inward = reversed(scene::cube());
  EXPECT_DOUBLE_EQ(signedVolume(inward), -8.0);
  const BackPatchValidity v = decide(inward);
  EXPECT_FALSE(v.enabled);
  EXPECT_TRUE(contains(v.reason, "inward")) << v.reason;
}

TEST(BoundValidity, OpenMeshesAreDisabledWithTheReason) {
  CageMesh open = scene::cube();
  open.faceSizes.pop_back();
  open.faceVertices.resize(open.faceVertices.size() - 4);
  BackPatchValidity v = decide(open);
  EXPECT_FALSE(v.enabled);
  EXPECT_TRUE(contains(v.reason, "4 boundary edges")) << v.reason;

  CageMesh holed = scene::cube();
  holed.holes = {2};
  v = decide(holed);
  EXPECT_FALSE(v.enabled);
  EXPECT_TRUE(contains(v.reason, "hole")) << v.reason;
}

// cullablePatches() decides from the refiner it extracts with (one refiner, not two): the
// same decision as from a refiner of its own, on closed, open, holed and inward meshes,
// and the patches equal extractPatches()'.
TEST(BoundValidity, CullablePatchesDecideLikeASecondRefinerWould) {
  CageMesh open = scene::cube();
  open.faceSizes.pop_back();
  open.faceVertices.resize(open.faceVertices.size() - 4);
  CageMesh holed = scene::cube();
  holed.holes = {2};
  CageMesh moved = scene::cube();
  for (glm::dvec3& p : moved.positions) p = p * 1e-3 + glm::dvec3(1e6, -2e6, 5e5);
  for (const CageMesh& m : {scene::cube(), reversed(scene::cube()), open, holed, moved}) {
    const BackPatchValidity alone = decide(m);
    const CullablePatches c = cullablePatches(m, PatchOptions{2});
    EXPECT_EQ(c.backPatch.enabled, alone.enabled) << alone.reason;
    EXPECT_EQ(c.backPatch.reason, alone.reason);
    EXPECT_EQ(c.extraction.topology.faces, summarize(*makeTopologyRefiner(m)).faces);
    const PatchExtraction ex = extractPatches(m, PatchOptions{2});
    EXPECT_EQ(c.extraction.patches.patchCount(), ex.patches.patchCount());
    EXPECT_EQ(c.extraction.patches.points, ex.patches.points);
  }
}

TEST(BoundValidity, NonManifoldOrInconsistentlyOrientedMeshesAreDisabled) {
  // One face turned over: its four edges are traversed twice in the same direction.
  CageMesh flipped = scene::cube();
  std::reverse(flipped.faceVertices.begin(), flipped.faceVertices.begin() + 4);
  // OpenSubdiv splits the conflicting edges (some become boundary edges, some
  // non-manifold); either way the surface is no longer a closed oriented manifold.
  const TopologySummary ft = summarize(*makeTopologyRefiner(flipped));
  EXPECT_FALSE(ft.closed);
  BackPatchValidity v = decide(flipped);
  EXPECT_FALSE(v.enabled) << v.reason;
  // A fin: a third face on the edge 0-1.
  CageMesh fin = scene::cube();
  fin.positions.push_back({0.0, -3.0, -1.0});
  fin.positions.push_back({0.0, -3.0, 1.0});
  fin.faceSizes.push_back(4);
  for (int i : {0, 1, 9, 8}) fin.faceVertices.push_back(i);
  v = decide(fin);
  EXPECT_FALSE(v.enabled);
  EXPECT_TRUE(contains(v.reason, "non-manifold")) << v.reason;
  // No faces at all.
  TopologySummary empty;
  EXPECT_FALSE(backPatchValidity(empty, 0.0).enabled);
}

TEST(BoundValidity, OpenSubdivPatchNormalsBuCrossBvPointOutOfACounterClockwiseCube) {
  // The convention every back-patch test relies on, on OpenSubdiv's own patches (regular
  // B-spline and Gregory basis), evaluated with OpenSubdiv's basis functions.
  const CageMesh cube = scene::cube();
  const PatchSet set = extractPatches(cube).patches;  // one per OpenSubdiv patch, with its param
  const osd_cull::test::OsdReference osd(cube, PatchOptions{});
  int checked = 0;
  for (uint32_t p = 0; p < set.patchCount(); ++p)
    for (double s : {0.25, 0.75})
      for (double t : {0.25, 0.75}) {
        SurfacePoint theirs;
        ASSERT_TRUE(osd.evaluate(set.params[p], s, t, theirs)) << "patch " << p;
        // The limit surface of the cube is convex around the origin.
        EXPECT_GT(glm::dot(glm::cross(theirs.du, theirs.dv), theirs.position), 0.0)
            << "patch " << p;
        ++checked;
      }
  EXPECT_EQ(checked, 4 * static_cast<int>(set.patchCount()));
  EXPECT_GT(set.patchCount(), 0u);
}

TEST(BoundValidity, RegularPatchesConvertedToBezierKeepOpenSubdivsParameterization) {
  // The B-spline -> Bézier conversion used by the rate tests must keep u and v (a transposed
  // patch would flip N and with it every back-patch decision).
  const CageMesh cube = scene::cube();
  PatchOptions options;
  options.isolationLevel = 3;
  const test::CagePatches patches = test::cagePatches(cube, 3);
  const PatchSet& set = patches.extraction.patches;
  const osd_cull::test::OsdReference osd(cube, options);
  size_t checked = 0;
  for (uint32_t p = 0; p < set.bezierCount; ++p) {
    if (set.origins[p] != PatchOrigin::Regular) continue;
    const double s = 0.3, t = 0.6;
    // OpenSubdiv's derivatives with respect to the patch's own parameters (its face
    // derivatives scaled by the patch's parametric size).
    SurfacePoint theirs;
    ASSERT_TRUE(osd.evaluate(set.params[p], s, t, theirs)) << "patch " << p;
    const PatchSample mine = evaluateBezier(patches.bezier.at(p), s, t);
    EXPECT_NEAR(glm::length(mine.position - theirs.position), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(mine.du - theirs.du), 0.0, 1e-5 * glm::length(mine.du));
    EXPECT_NEAR(glm::length(mine.dv - theirs.dv), 0.0, 1e-5 * glm::length(mine.dv));
    ++checked;
  }
  EXPECT_EQ(checked, patches.extraction.stats.regular);
  EXPECT_GT(checked, 0u);
}

TEST(BoundValidity, SharedShapesLeftHandedIsDisabledClosedOnesEnabled) {
  OSD_CULL_REQUIRE_DATA();
  const auto dir = osd_cull::test::dataDir() / "shapes";
  for (const char* name :
       {"catmark_cube", "catmark_torus", "catmark_pyramid_creases0", "catmark_toroidal_tet"}) {
    const BackPatchValidity v = decide(adapters::loadCage(dir / (std::string(name) + ".obj")));
    EXPECT_TRUE(v.enabled) << name << ": " << v.reason;
  }
  const BackPatchValidity left = decide(adapters::loadCage(dir / "catmark_lefthanded.obj"));
  EXPECT_FALSE(left.enabled);
  EXPECT_TRUE(contains(left.reason, "inward")) << left.reason;
  const BackPatchValidity open = decide(adapters::loadCage(dir / "catmark_nonman_edges.obj"));
  EXPECT_FALSE(open.enabled) << open.reason;
}

}  // namespace
}  // namespace osd_cull::bound
