// The tagged-OBJ reader on small texts written to temporary files: OpenSubdiv's tags,
// index forms, and the OBJ statements that are accepted or noted.
#include "adapters/load_mesh.h"
#include "osd_cull/error.h"
#include "osd_cull/patch/refiner.h"
#include "support/temp_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;
using adapters::loadCage;
using Options = OpenSubdiv::Sdc::Options;

// A temp folder whose name says which suite wrote it.
struct TempDir : test::TempDir {
  TempDir() : test::TempDir("osd_cull_obj_") {}
};

// A 3x3 grid of quads on 4x4 vertices (vertex r*4+c); edges 4-5, 5-6, 6-7 are interior.
const std::string kGrid =
    "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\n"
    "v 0 1 0\nv 1 1 0\nv 2 1 0\nv 3 1 0\n"
    "v 0 2 0\nv 1 2 0\nv 2 2 0\nv 3 2 0\n"
    "v 0 3 0\nv 1 3 0\nv 2 3 0\nv 3 3 0\n"
    "f 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n"
    "f 5 6 10 9\nf 6 7 11 10\nf 7 8 12 11\n"
    "f 9 10 14 13\nf 10 11 15 14\nf 11 12 16 15\n";

float edgeSharpness(const Far::TopologyRefiner& r, int a, int b) {
  const auto& level = r.GetLevel(0);
  const int e = level.FindEdge(a, b);
  EXPECT_NE(e, OpenSubdiv::Far::INDEX_INVALID) << a << "-" << b;
  return e == OpenSubdiv::Far::INDEX_INVALID ? -1.0f : level.GetEdgeSharpness(e);
}

bool hasNoteWith(const CageMesh& m, const std::string& text) {
  for (const std::string& n : m.notes)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

TEST(ObjTags, CreaseChainMakesOneEdgePerConsecutivePair) {
  TempDir dir;
  const CageMesh m = loadCage(dir.write("grid.obj", kGrid + "t crease 4/1/0 4 5 6 7 2.5\n"));
  ASSERT_EQ(m.creases.size(), 3u);
  EXPECT_EQ(m.creases[0].v0, 4);
  EXPECT_EQ(m.creases[0].v1, 5);
  EXPECT_EQ(m.creases[2].v0, 6);
  EXPECT_EQ(m.creases[2].v1, 7);
  const auto r = makeTopologyRefiner(m);
  EXPECT_FLOAT_EQ(edgeSharpness(*r, 4, 5), 2.5f);
  EXPECT_FLOAT_EQ(edgeSharpness(*r, 5, 6), 2.5f);
  EXPECT_FLOAT_EQ(edgeSharpness(*r, 6, 7), 2.5f);
  EXPECT_FLOAT_EQ(edgeSharpness(*r, 8, 9), 0.0f);
  EXPECT_EQ(summarize(*r).creasedEdges, 3);  // tagged interior edges; boundary edges are not counted
}

TEST(ObjTags, CreaseTakesOneSharpnessPerEdge) {
  TempDir dir;
  const auto r = makeTopologyRefiner(
      loadCage(dir.write("grid.obj", kGrid + "t crease 3/2/0 4 5 6 1.0 3.0\n")));
  EXPECT_FLOAT_EQ(edgeSharpness(*r, 4, 5), 1.0f);
  EXPECT_FLOAT_EQ(edgeSharpness(*r, 5, 6), 3.0f);
  EXPECT_FLOAT_EQ(edgeSharpness(*r, 6, 7), 0.0f);
}

TEST(ObjTags, LaterCreaseOnTheSameEdgeWins) {
  TempDir dir;
  const auto r = makeTopologyRefiner(
      loadCage(dir.write("grid.obj", kGrid + "t crease 2/1/0 5 6 1.0\nt crease 2/1/0 6 5 4.0\n")));
  EXPECT_FLOAT_EQ(edgeSharpness(*r, 5, 6), 4.0f);
}

TEST(ObjTags, NegativeSharpnessIsClampedToZeroWithANote) {
  TempDir dir;
  const CageMesh m = loadCage(dir.write("grid.obj", kGrid + "t crease 2/1/0 5 6 -2\n"));
  ASSERT_EQ(m.creases.size(), 1u);
  EXPECT_EQ(m.creases[0].sharpness, 0.0f);
  EXPECT_TRUE(hasNoteWith(m, "clamped")) << ::testing::PrintToString(m.notes);
}

TEST(ObjTags, CornersTakeOneSharpnessForAllOrOneEach) {
  TempDir dir;
  const CageMesh all = loadCage(dir.write("a.obj", kGrid + "t corner 2/1/0 5 10 4.0\n"));
  const auto ra = makeTopologyRefiner(all);
  EXPECT_FLOAT_EQ(ra->GetLevel(0).GetVertexSharpness(5), 4.0f);
  EXPECT_FLOAT_EQ(ra->GetLevel(0).GetVertexSharpness(10), 4.0f);
  EXPECT_FLOAT_EQ(ra->GetLevel(0).GetVertexSharpness(6), 0.0f);
  const auto re =
      makeTopologyRefiner(loadCage(dir.write("e.obj", kGrid + "t corner 2/2/0 5 10 1.5 7\n")));
  EXPECT_FLOAT_EQ(re->GetLevel(0).GetVertexSharpness(5), 1.5f);
  EXPECT_FLOAT_EQ(re->GetLevel(0).GetVertexSharpness(10), 7.0f);
}

TEST(ObjTags, HoleTagsMarkFacesByZeroBasedIndex) {
  TempDir dir;
  const CageMesh m = loadCage(dir.write("grid.obj", kGrid + "t hole 2/0/0 0 4\n"));
  EXPECT_EQ(m.holes, (std::vector<int>{0, 4}));
  const auto r = makeTopologyRefiner(m);
  EXPECT_TRUE(r->GetLevel(0).IsFaceHole(0));
  EXPECT_TRUE(r->GetLevel(0).IsFaceHole(4));
  EXPECT_FALSE(r->GetLevel(0).IsFaceHole(1));
  EXPECT_EQ(summarize(*r).holes, 2);
}

TEST(ObjTags, InterpolateBoundaryMapsLikeOpenSubdivsHarness) {
  TempDir dir;
  auto rule = [&](const std::string& tag) {
    return makeTopologyRefiner(loadCage(dir.write("g.obj", kGrid + tag)))
        ->GetSchemeOptions()
        .GetVtxBoundaryInterpolation();
  };
  EXPECT_EQ(rule(""), Options::VTX_BOUNDARY_EDGE_ONLY);  // the harness default
  EXPECT_EQ(rule("t interpolateboundary 1/0/0 0\n"), Options::VTX_BOUNDARY_NONE);
  EXPECT_EQ(rule("t interpolateboundary 1/0/0 1\n"), Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  EXPECT_EQ(rule("t interpolateboundary 1/0/0 2\n"), Options::VTX_BOUNDARY_EDGE_ONLY);
}

TEST(ObjTags, FaceVaryingBoundaryMapsZeroToFive) {
  TempDir dir;
  const Options::FVarLinearInterpolation expected[] = {
      Options::FVAR_LINEAR_NONE,          Options::FVAR_LINEAR_CORNERS_ONLY,
      Options::FVAR_LINEAR_CORNERS_PLUS1, Options::FVAR_LINEAR_CORNERS_PLUS2,
      Options::FVAR_LINEAR_BOUNDARIES,    Options::FVAR_LINEAR_ALL};
  for (int i = 0; i < 6; ++i) {
    const CageMesh m = loadCage(dir.write(
        "g.obj", kGrid + "t facevaryinginterpolateboundary 1/0/0 " + std::to_string(i) + "\n"));
    EXPECT_EQ(makeTopologyRefiner(m)->GetSchemeOptions().GetFVarLinearInterpolation(), expected[i])
        << i;
  }
  EXPECT_EQ(loadCage(dir.write("d.obj", kGrid)).fvarBoundary, FVarInterpolation::All);
}

TEST(ObjTags, CreaseMethodAndSmoothTriangles) {
  TempDir dir;
  EXPECT_EQ(loadCage(dir.write("a.obj", kGrid + "t creasemethod 0/0/1 chaikin\n")).creasing,
            CreasingMethod::Chaikin);
  EXPECT_EQ(loadCage(dir.write("b.obj", kGrid + "t creasemethod 0/0/1 normal\n")).creasing,
            CreasingMethod::Uniform);
  EXPECT_EQ(loadCage(dir.write("c.obj", kGrid + "t creasemethod 0/0/1 uniform\n")).creasing,
            CreasingMethod::Uniform);
  const CageMesh smooth = loadCage(dir.write("d.obj", kGrid + "t smoothtriangles 0/0/1 smooth\n"));
  EXPECT_EQ(makeTopologyRefiner(smooth)->GetSchemeOptions().GetTriangleSubdivision(),
            Options::TRI_SUB_SMOOTH);
  EXPECT_EQ(loadCage(dir.write("e.obj", kGrid + "t smoothtriangles 0/0/1 catmark\n")).triangles,
            TriangleSubdivision::Catmark);
  // Only Catmull-Clark has triangle weights: on another scheme the tag is noted and ignored.
  const CageMesh bilinear =
      loadCage(dir.write("bilinear_f.obj", kGrid + "t smoothtriangles 0/0/1 smooth\n"));
  EXPECT_EQ(bilinear.triangles, TriangleSubdivision::Catmark);
  EXPECT_TRUE(hasNoteWith(bilinear, "smoothtriangles")) << ::testing::PrintToString(bilinear.notes);
}

TEST(ObjTags, UnknownTagsAndExtraArgumentsAreNotedNotErrors) {
  TempDir dir;
  const CageMesh m = loadCage(dir.write("g.obj", kGrid + "t facevaryingpropagatecorners 1/0/0 1\n"
                                                         "t interpolateboundary 1/0/0 1 extra\n"));
  EXPECT_TRUE(hasNoteWith(m, "'facevaryingpropagatecorners'")) << ::testing::PrintToString(m.notes);
  EXPECT_TRUE(hasNoteWith(m, "more arguments than declared")) << ::testing::PrintToString(m.notes);
  EXPECT_EQ(m.boundary, BoundaryInterpolation::EdgeAndCorner);
}

TEST(ObjTags, HashTLineIsAComment) {
  TempDir dir;
  const CageMesh m =
      loadCage(dir.write("g.obj", kGrid + "#t crease 2/1/0 5 6 3.0\n# t hole 1/0/0 0\n"));
  EXPECT_TRUE(m.creases.empty());
  EXPECT_TRUE(m.holes.empty());
  EXPECT_TRUE(m.notes.empty()) << ::testing::PrintToString(m.notes);
}

TEST(ObjIndices, NegativeIndicesCountBackFromTheLastVertex) {
  TempDir dir;
  const CageMesh m = loadCage(dir.write("n.obj",
                                        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2 -1\n"
                                        "v 2 0 0\nv 2 1 0\nf -5 -2 -1 -4\n"));
  EXPECT_EQ(m.faceVertices, (std::vector<int>{0, 1, 2, 3, 1, 4, 5, 2}));
}

TEST(ObjIndices, AllCornerFormsGiveTheSameFaces) {
  TempDir dir;
  const std::string head =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n";
  const std::vector<int> expected = {0, 1, 2, 3};
  EXPECT_EQ(loadCage(dir.write("a.obj", head + "f 1 2 3 4\n")).faceVertices, expected);
  EXPECT_EQ(loadCage(dir.write("b.obj", head + "f 1/1 2/2 3/3 4/4\n")).faceVertices, expected);
  EXPECT_EQ(loadCage(dir.write("c.obj", head + "f 1//1 2//1 3//1 4//1\n")).faceVertices, expected);
  EXPECT_EQ(loadCage(dir.write("d.obj", head + "f 1/1/1 2/2/1 3/3/1 4/4/1\n")).faceVertices,
            expected);
  EXPECT_EQ(
      loadCage(dir.write("e.obj", head + "f -4/-4/-1 -3/-3/-1 -2/-2/-1 -1/-1/-1\n")).faceVertices,
      expected);
}

TEST(ObjIndices, FacesMayReferToVerticesDefinedLater) {
  TempDir dir;
  const CageMesh m = loadCage(dir.write("late.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"));
  EXPECT_EQ(m.faceCount(), 1);
  EXPECT_EQ(m.vertexCount(), 3);
}

TEST(ObjSyntax, CrlfBlankLinesCommentsAndContinuations) {
  TempDir dir;
  const CageMesh m =
      loadCage(dir.write("crlf.obj",
                         "# comment\r\n\r\nv 0 0 0\r\nv 1 0 0 1.0\r\n   \r\nv 1 1 0 0.5 0.5 0.5\r\n"
                         "v 0 1 0\r\nf 1 2 \\\r\n 3 4 # trailing comment\r\n"
                         "t crease 2/1/0 0 1 \\\n 2.0\n"));
  EXPECT_EQ(m.vertexCount(), 4);
  EXPECT_EQ(m.faceVertices, (std::vector<int>{0, 1, 2, 3}));
  ASSERT_EQ(m.creases.size(), 1u);
  EXPECT_EQ(m.creases[0].sharpness, 2.0f);
}

TEST(ObjSyntax, GroupsSmoothingObjectsAndMaterialsAreAccepted) {
  TempDir dir;
  const CageMesh m =
      loadCage(dir.write("m.obj",
                         "mtllib missing.mtl\no thing\ng a b\ns off\ns 1\nusemtl red\n"
                         "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_EQ(m.faceCount(), 1);
  ASSERT_EQ(m.notes.size(), 1u) << ::testing::PrintToString(m.notes);
  EXPECT_NE(m.notes[0].find("missing.mtl"), std::string::npos);
  EXPECT_NE(m.notes[0].find(":1:"), std::string::npos);
  dir.write("present.mtl", "newmtl red\n");
  EXPECT_TRUE(
      loadCage(dir.write("p.obj", "mtllib present.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"))
          .notes.empty());
}

TEST(ObjSyntax, UnknownKeywordsAreNotedWithCountAndFirstLine) {
  TempDir dir;
  const CageMesh m = loadCage(
      dir.write("u.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nf 1 2 3\nl 2 3\ncurv 0 1 1 2\n"));
  EXPECT_TRUE(hasNoteWith(m, "2 line(s) with unknown keyword 'l' (first at line 4)"))
      << ::testing::PrintToString(m.notes);
  EXPECT_TRUE(hasNoteWith(m, "'curv'"));
}

TEST(ObjTopology, FaceRepeatingAVertexReachesOpenSubdivWithANote) {
  TempDir dir;
  const CageMesh m = loadCage(dir.write("rep.obj", kGrid + "f 4 3 5 5\n"));
  EXPECT_EQ(std::vector<int>(m.faceVertices.end() - 4, m.faceVertices.end()),
            (std::vector<int>{3, 2, 4, 4}));
  EXPECT_TRUE(hasNoteWith(m, "1 face repeats a vertex (first: face 9 uses vertex 4 twice)"))
      << ::testing::PrintToString(m.notes);
  EXPECT_EQ(summarize(*makeTopologyRefiner(m)).degenerateFaces, 1);
}

TEST(ObjTopology, UnusedVerticesAndNonManifoldEdgesAreNoted) {
  TempDir dir;
  // Three triangles on the edge 1-2 (a fin) and a vertex no face uses.
  const CageMesh m = loadCage(dir.write("fin.obj",
                                        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 9 9 9\n"
                                        "f 1 2 3\nf 2 1 4\nf 1 2 5\n"));
  EXPECT_TRUE(hasNoteWith(m, "1 vertex is used by no face (first: vertex 5)"))
      << ::testing::PrintToString(m.notes);
  EXPECT_TRUE(hasNoteWith(m, "1 edge is shared by more than two faces"))
      << ::testing::PrintToString(m.notes);
  const TopologySummary s = summarize(*makeTopologyRefiner(m));
  EXPECT_EQ(s.nonManifoldEdges, 1);
  EXPECT_EQ(s.unusedVertices, 1);
}

TEST(ObjTopology, InconsistentOrientationIsNoted) {
  TempDir dir;
  // Two quads sharing the edge 2-3 (1-based), the second wound the other way: both
  // traverse 2 -> 3.
  const std::string verts = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n";
  const CageMesh flipped = loadCage(dir.write("flip.obj", verts + "f 1 2 3 4\nf 3 6 5 2\n"));
  EXPECT_TRUE(
      hasNoteWith(flipped,
                  "1 edge is traversed twice in the same direction (inconsistent orientation; "
                  "first: edge (1, 2))"))
      << ::testing::PrintToString(flipped.notes);
  EXPECT_EQ(summarize(*makeTopologyRefiner(flipped)).faces, 2);
  EXPECT_TRUE(loadCage(dir.write("ok.obj", verts + "f 1 2 3 4\nf 2 5 6 3\n")).notes.empty());
}

TEST(ObjScheme, FileNamePrefixThenDefault) {
  TempDir dir;
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_EQ(loadCage(dir.write("loop_tri.obj", tri)).scheme, Scheme::Loop);
  EXPECT_EQ(loadCage(dir.write("bilinear_tri.obj", tri)).scheme, Scheme::Bilinear);
  EXPECT_EQ(loadCage(dir.write("catmark_tri.obj", tri)).scheme, Scheme::CatmullClark);
  EXPECT_EQ(loadCage(dir.write("tri.OBJ", tri)).scheme, Scheme::CatmullClark);
  adapters::LoadOptions loop;
  loop.scheme = Scheme::Loop;
  EXPECT_EQ(loadCage(dir.write("catmark_x.obj", tri), loop).scheme, Scheme::Loop);
}

}  // namespace
}  // namespace osd_cull
