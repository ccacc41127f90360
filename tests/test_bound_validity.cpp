// When back-patch culling may be used on a mesh (closed, manifold, oriented outward), and
// the orientation convention N = Bu x Bv checked against OpenSubdiv's own patches.
#include "osd_cull/bound/back_patch_validity.h"
#include "support/test_data.h"
#include "test_bound_fixtures.h"

#include <gtest/gtest.h>

#include <string>

namespace osd_cull::bound {
namespace {

namespace Far = OpenSubdiv::Far;

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
  const CageMesh cube = test::cubeCage();
  EXPECT_DOUBLE_EQ(signedVolume(cube), 8.0);
  const BackPatchValidity v = decide(cube);
  EXPECT_TRUE(v.enabled) << v.reason;
  // Without a volume the topology alone enables it and says what was assumed.
  const BackPatchValidity assumed = backPatchValidity(summarize(*makeTopologyRefiner(cube)));
  EXPECT_TRUE(assumed.enabled);
  EXPECT_TRUE(contains(assumed.reason, "assumed")) << assumed.reason;
}

TEST(BoundValidity, InwardOrientedCubeIsDisabled) {
  const CageMesh inward = reversed(test::cubeCage());
  EXPECT_DOUBLE_EQ(signedVolume(inward), -8.0);
  const BackPatchValidity v = decide(inward);
  EXPECT_FALSE(v.enabled);
  EXPECT_TRUE(contains(v.reason, "inward")) << v.reason;
}

TEST(BoundValidity, OpenMeshesAreDisabledWithTheReason) {
  CageMesh open = test::cubeCage();
  open.faceSizes.pop_back();
  open.faceVertices.resize(open.faceVertices.size() - 4);
  BackPatchValidity v = decide(open);
  EXPECT_FALSE(v.enabled);
  EXPECT_TRUE(contains(v.reason, "4 boundary edges")) << v.reason;

  CageMesh holed = test::cubeCage();
  holed.holes = {2};
  v = decide(holed);
  EXPECT_FALSE(v.enabled);
  EXPECT_TRUE(contains(v.reason, "hole")) << v.reason;
}

TEST(BoundValidity, NonManifoldOrInconsistentlyOrientedMeshesAreDisabled) {
  // One face turned over: its four edges are traversed twice in the same direction.
  CageMesh flipped = test::cubeCage();
  std::reverse(flipped.faceVertices.begin(), flipped.faceVertices.begin() + 4);
  // OpenSubdiv splits the conflicting edges (some become boundary edges, some
  // non-manifold); either way the surface is no longer a closed oriented manifold.
  const TopologySummary ft = summarize(*makeTopologyRefiner(flipped));
  EXPECT_FALSE(ft.closed);
  BackPatchValidity v = decide(flipped);
  EXPECT_FALSE(v.enabled) << v.reason;
  // A fin: a third face on the edge 0-1.
  CageMesh fin = test::cubeCage();
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
  const test::OsdPatches osd = test::buildOsdPatches(test::cubeCage(), 2);
  const Far::PatchTable& table = *osd.table;
  int checked = 0, firstPatch = 0;
  for (int a = 0; a < table.GetNumPatchArrays(); ++a) {
    const int cvCount = table.GetPatchArrayDescriptor(a).GetNumControlVertices();
    for (int p = 0; p < table.GetNumPatches(a); ++p) {
      Far::PatchTable::PatchHandle h;
      h.arrayIndex = a;
      h.patchIndex = firstPatch + p;
      h.vertIndex = p * cvCount;
      const auto cvs = table.GetPatchVertices(h);
      const Far::PatchParam param = table.GetPatchParam(h);
      for (double s : {0.25, 0.75})
        for (double t : {0.25, 0.75}) {
          double u = s, v = t;
          param.Unnormalize(u, v);
          double w[20], wu[20], wv[20];
          table.EvaluateBasis(h, u, v, w, wu, wv);
          glm::dvec3 pos(0.0), du(0.0), dv(0.0);
          for (int k = 0; k < cvCount; ++k) {
            pos += w[k] * osd.points[cvs[k]];
            du += wu[k] * osd.points[cvs[k]];
            dv += wv[k] * osd.points[cvs[k]];
          }
          // The limit surface of the cube is convex around the origin.
          EXPECT_GT(glm::dot(glm::cross(du, dv), pos), 0.0) << "array " << a << " patch " << p;
          ++checked;
        }
    }
    firstPatch += table.GetNumPatches(a);
  }
  EXPECT_EQ(checked, 4 * firstPatch);
  EXPECT_GT(firstPatch, 0);
}

TEST(BoundValidity, RegularPatchesConvertedToBezierKeepOpenSubdivsParameterization) {
  // The B-spline -> Bézier conversion used by the rate tests must keep u and v (a transposed
  // patch would flip N and with it every back-patch decision).
  const test::OsdPatches osd = test::buildOsdPatches(test::cubeCage(), 3);
  int skipped = 0;
  const std::vector<test::Bezier> bezier = test::regularPatchesAsBezier(osd, &skipped);
  const Far::PatchTable& table = *osd.table;
  size_t next = 0;
  int firstPatch = 0;
  for (int a = 0; a < table.GetNumPatchArrays(); ++a) {
    const Far::PatchDescriptor desc = table.GetPatchArrayDescriptor(a);
    for (int p = 0; p < table.GetNumPatches(a); ++p) {
      if (desc.GetType() != Far::PatchDescriptor::REGULAR ||
          table.GetPatchParam(a, p).GetBoundary())
        continue;
      Far::PatchTable::PatchHandle h;
      h.arrayIndex = a;
      h.patchIndex = firstPatch + p;
      h.vertIndex = p * desc.GetNumControlVertices();
      const auto cvs = table.GetPatchVertices(h);
      const Far::PatchParam param = table.GetPatchParam(h);
      const double s = 0.3, t = 0.6;
      double u = s, v = t;
      param.Unnormalize(u, v);
      double w[16], wu[16], wv[16];
      table.EvaluateBasis(h, u, v, w, wu, wv);
      glm::dvec3 pos(0.0), du(0.0), dv(0.0);
      for (int k = 0; k < 16; ++k) {
        pos += w[k] * osd.points[cvs[k]];
        du += wu[k] * osd.points[cvs[k]];
        dv += wv[k] * osd.points[cvs[k]];
      }
      // OpenSubdiv differentiates with respect to the face's parameters: scale by the
      // patch's parametric size to compare with the patch-local derivatives.
      const double f = param.GetParamFraction();
      const PatchSample mine = evaluateBezier(bezier.at(next++), s, t);
      EXPECT_NEAR(glm::length(mine.position - pos), 0.0, 1e-6);
      EXPECT_NEAR(glm::length(mine.du - f * du), 0.0, 1e-5 * glm::length(mine.du));
      EXPECT_NEAR(glm::length(mine.dv - f * dv), 0.0, 1e-5 * glm::length(mine.dv));
    }
    firstPatch += table.GetNumPatches(a);
  }
  EXPECT_EQ(next, bezier.size());
  EXPECT_GT(next, 0u);
}

TEST(BoundValidity, SharedShapesLeftHandedIsDisabledClosedOnesEnabled) {
  OSD_CULL_REQUIRE_DATA();
  const auto dir = osd_cull::test::dataDir() / "shapes";
  for (const char* name :
       {"catmark_cube", "catmark_torus", "catmark_pyramid_creases0", "catmark_toroidal_tet"}) {
    const BackPatchValidity v = decide(test::readObjFaces(dir / (std::string(name) + ".obj")));
    EXPECT_TRUE(v.enabled) << name << ": " << v.reason;
  }
  const BackPatchValidity left = decide(test::readObjFaces(dir / "catmark_lefthanded.obj"));
  EXPECT_FALSE(left.enabled);
  EXPECT_TRUE(contains(left.reason, "inward")) << left.reason;
  const BackPatchValidity open = decide(test::readObjFaces(dir / "catmark_nonman_edges.obj"));
  EXPECT_FALSE(open.enabled) << open.reason;
}

}  // namespace
}  // namespace osd_cull::bound
