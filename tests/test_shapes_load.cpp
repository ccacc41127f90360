// Every OpenSubdiv regression shape and BigGuy loads, builds a refiner, and matches the
// facts listed in data/shapes/INDEX.tsv and data/characters/INDEX.tsv column by column.
#include "adapters/load_mesh.h"
#include "adapters/topology_notes.h"
#include "osd_cull/patch/refiner.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;

struct IndexRow {
  fs::path file;
  std::map<std::string, std::string> col;
  int num(const std::string& name) const { return std::stoi(col.at(name)); }
  bool yes(const std::string& name) const { return col.at(name) == "yes"; }
};

// Test names and failure messages show the shape's name.
void PrintTo(const IndexRow& row, std::ostream* os) { *os << row.col.at("name"); }

std::vector<std::string> splitTabs(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, '\t');) out.push_back(cell);
  return out;
}

std::vector<IndexRow> readIndex(const fs::path& folder) {
  std::vector<IndexRow> rows;
  std::ifstream in(folder / "INDEX.tsv");
  std::string line;
  if (!std::getline(in, line)) return rows;
  const std::vector<std::string> header = splitTabs(line);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = splitTabs(line);
    IndexRow row;
    for (size_t i = 0; i < header.size() && i < cells.size(); ++i) row.col[header[i]] = cells[i];
    row.file = folder / (row.col["name"] + ".obj");
    rows.push_back(row);
  }
  return rows;
}

std::vector<IndexRow> allRows() {
  std::vector<IndexRow> rows;
  // Without the data folder: one row without a file, whose test skips naming the folder.
  if (!test::haveData()) return {IndexRow{{}, {{"name", "NoData"}}}};
  for (const char* folder : {"shapes", "characters"}) {
    auto part = readIndex(test::dataDir() / folder);
    rows.insert(rows.end(), part.begin(), part.end());
  }
  return rows;
}

// --- Reference facts computed here from the face list, independently of the loader's notes.

// Connected components of the faces (faces sharing a vertex are connected).
int faceComponents(const CageMesh& m) {
  std::vector<int> parent(m.positions.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::set<int> used;
  for (size_t f = 0, o = 0; f < m.faceSizes.size(); o += m.faceSizes[f++])
    for (int k = 0; k < m.faceSizes[f]; ++k) {
      used.insert(m.faceVertices[o + k]);
      parent[find(m.faceVertices[o + k])] = find(m.faceVertices[o]);
    }
  std::set<int> roots;
  for (int v : used) roots.insert(find(v));
  return static_cast<int>(roots.size());
}

// The INDEX's Euler characteristic: used vertices - distinct edges (collapsed v-v edges of
// degenerate faces excluded) + faces.
int indexEulerCharacteristic(const CageMesh& m) {
  std::set<int> used(m.faceVertices.begin(), m.faceVertices.end());
  std::set<std::pair<int, int>> edges;
  for (size_t f = 0, o = 0; f < m.faceSizes.size(); o += m.faceSizes[f++])
    for (int k = 0; k < m.faceSizes[f]; ++k) {
      const int a = m.faceVertices[o + k], b = m.faceVertices[o + (k + 1) % m.faceSizes[f]];
      if (a != b) edges.insert({std::min(a, b), std::max(a, b)});
    }
  return static_cast<int>(used.size()) - static_cast<int>(edges.size()) + m.faceCount();
}

// --- The tag lines, read by a deliberately naive second parser (the shapes use only the
// simple forms: two-vertex creases, one-vertex corners, one hole, one value per option).
struct FileTags {
  std::map<std::pair<int, int>, float> creases;  // last tag wins, as in OpenSubdiv
  std::map<int, float> corners;
  std::set<int> holes;
  std::map<std::string, int> lines;          // tag name → number of tag lines
  std::map<std::string, std::string> value;  // option tags → last argument
};

FileTags readTagsNaively(const fs::path& file) {
  FileTags t;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    std::stringstream ss(line);
    std::string key, name, counts;
    ss >> key >> name >> counts;
    if (key != "t") continue;
    ++t.lines[name];
    std::vector<std::string> args;
    for (std::string a; ss >> a;) args.push_back(a);
    if (name == "crease") {
      const int a = std::stoi(args[0]), b = std::stoi(args[1]);
      t.creases[{std::min(a, b), std::max(a, b)}] = std::stof(args[2]);
    } else if (name == "corner") {
      t.corners[std::stoi(args[0])] = std::stof(args[1]);
    } else if (name == "hole") {
      t.holes.insert(std::stoi(args[0]));
    } else {
      t.value[name] = args.back();
    }
  }
  return t;
}

std::map<std::string, int> parseTagKinds(const std::string& text) {
  std::map<std::string, int> kinds;
  if (text == "-") return kinds;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    const size_t colon = item.find(':');
    kinds[item.substr(0, colon)] = std::stoi(item.substr(colon + 1));
  }
  return kinds;
}

// Where OpenSubdiv's view of the base level legitimately differs from the INDEX (which
// counts like a half-edge mesh library). OpenSubdiv keeps the collapsed v-v edge of a face
// that repeats a vertex as an edge of its own and marks it, and every edge whose faces
// disagree on orientation, non-manifold; those extra edges also enter the vertices' edge
// lists (valence). A vertex no face uses is non-manifold to OpenSubdiv.
struct OsdView {
  int nonManifoldEdges, nonManifoldVertices, maxValence;
};
const std::map<std::string, OsdView>& osdExceptions() {
  static const std::map<std::string, OsdView> table = {
      // 9 edges with 3+ faces, 15 orientation conflicts and 14 degenerate faces' edges
      {"catmark_nonman_edges", {37, 24, 24}},
      // 8 faces "f a b c c": 8 collapsed edges (c, c), all at the pole vertex
      {"catmark_nonman_quadpole8", {8, 1, 24}},
      // one unused vertex each
      {"catmark_nonman_verts", {0, 5, 8}},
      {"loop_nonman_verts", {0, 5, 12}},
  };
  return table;
}

class ShapeIndex : public ::testing::TestWithParam<IndexRow> {};

TEST_P(ShapeIndex, LoadsAndMatchesEveryIndexColumn) {
  const IndexRow& row = GetParam();
  if (row.file.empty()) OSD_CULL_REQUIRE_DATA();
  const CageMesh mesh = adapters::loadCage(row.file);
  const auto refiner = makeTopologyRefiner(mesh);
  const TopologySummary s = summarize(*refiner);

  EXPECT_EQ(toString(mesh.scheme), row.col.at("scheme"));
  EXPECT_EQ(s.vertices, row.num("vertices"));
  EXPECT_EQ(s.faces, row.num("faces"));
  EXPECT_EQ(*std::max_element(mesh.faceSizes.begin(), mesh.faceSizes.end()),
            row.num("max_face_valence"));
  EXPECT_EQ(s.triangles, row.num("tris"));
  EXPECT_EQ(s.quads, row.num("quads"));
  EXPECT_EQ(s.otherFaces, row.num("ngons"));
  EXPECT_EQ(s.boundaryEdges, row.num("boundary_edges"));
  EXPECT_EQ(s.unusedVertices, row.num("unused_verts"));
  EXPECT_EQ(s.degenerateFaces, row.num("degenerate_faces"));

  OsdView osd{row.num("nonmanifold_edges"), row.num("nonmanifold_verts"),
              row.num("max_vertex_valence")};
  if (auto it = osdExceptions().find(row.col.at("name")); it != osdExceptions().end())
    osd = it->second;
  EXPECT_EQ(s.nonManifoldEdges, osd.nonManifoldEdges);
  EXPECT_EQ(s.nonManifoldVertices, osd.nonManifoldVertices);
  EXPECT_EQ(s.maxValence, osd.maxValence);
  // The INDEX's "non_manifold" means edges with three or more faces.
  EXPECT_EQ(row.yes("non_manifold"), row.num("nonmanifold_edges") > 0);

  // The INDEX calls a mesh closed when it has no boundary and no non-manifold edge; to
  // summarize() (and to back-patch culling) a hole opens the surface too.
  const bool topologicallyClosed = s.boundaryEdges == 0 && s.nonManifoldEdges == 0;
  EXPECT_EQ(topologicallyClosed, row.yes("is_closed"));
  EXPECT_EQ(s.closed, row.yes("is_closed") && s.holes == 0);

  // The loader's own notes count what the INDEX counts.
  CageMesh copy = mesh;
  copy.notes.clear();
  const adapters::TopologyFindings found = adapters::noteTopology(copy);
  EXPECT_EQ(found.facesRepeatingAVertex, row.num("degenerate_faces"));
  EXPECT_EQ(found.unusedVertices, row.num("unused_verts"));
  EXPECT_EQ(found.edgesWithManyFaces, row.num("nonmanifold_edges"));
  EXPECT_EQ(found.orientationConflicts == 0, row.yes("orientation_consistent"));
  EXPECT_EQ(copy.notes.empty(), found.facesRepeatingAVertex + found.unusedVertices +
                                        found.edgesWithManyFaces + found.orientationConflicts ==
                                    0);

  EXPECT_EQ(faceComponents(mesh), row.num("components"));
  EXPECT_EQ(indexEulerCharacteristic(mesh), row.num("euler_char"));

  // Tags: the loader's result, OpenSubdiv's refiner and a naive reading of the file agree,
  // and the file has the tag lines the INDEX lists.
  const FileTags tags = readTagsNaively(row.file);
  EXPECT_EQ(tags.lines, parseTagKinds(row.col.at("tag_kinds")));
  EXPECT_EQ(row.yes("has_crease_tags"), !mesh.creases.empty() || !mesh.corners.empty());
  const Far::TopologyLevel& level = refiner->GetLevel(0);
  std::map<std::pair<int, int>, float> loadedCreases;
  for (const CreaseEdge& c : mesh.creases)
    loadedCreases[{std::min(c.v0, c.v1), std::max(c.v0, c.v1)}] = c.sharpness;
  EXPECT_EQ(loadedCreases, tags.creases);
  for (const auto& [edge, sharpness] : tags.creases) {
    const int e = level.FindEdge(edge.first, edge.second);
    ASSERT_NE(e, OpenSubdiv::Far::INDEX_INVALID);
    // OpenSubdiv makes boundary and non-manifold edges infinitely sharp whatever the tag.
    if (level.GetEdgeFaces(e).size() == 2 && !level.IsEdgeNonManifold(e)) {
      EXPECT_FLOAT_EQ(level.GetEdgeSharpness(e), sharpness)
          << "edge " << edge.first << "-" << edge.second;
    }
  }
  ASSERT_EQ(mesh.corners.size(), tags.corners.size());
  for (const CornerVertex& c : mesh.corners) {
    EXPECT_FLOAT_EQ(tags.corners.at(c.vertex), c.sharpness);
    EXPECT_FLOAT_EQ(level.GetVertexSharpness(c.vertex), c.sharpness);
  }
  EXPECT_EQ(std::set<int>(mesh.holes.begin(), mesh.holes.end()), tags.holes);
  EXPECT_EQ(s.holes, static_cast<int>(tags.holes.size()));
  for (int h : tags.holes) EXPECT_TRUE(level.IsFaceHole(h));

  const auto options = refiner->GetSchemeOptions();
  using Options = OpenSubdiv::Sdc::Options;
  Options::VtxBoundaryInterpolation boundary = Options::VTX_BOUNDARY_EDGE_ONLY;  // harness default
  if (tags.value.contains("interpolateboundary")) {
    const int v = std::stoi(tags.value.at("interpolateboundary"));
    boundary = v == 0   ? Options::VTX_BOUNDARY_NONE
               : v == 1 ? Options::VTX_BOUNDARY_EDGE_AND_CORNER
                        : Options::VTX_BOUNDARY_EDGE_ONLY;
  }
  EXPECT_EQ(options.GetVtxBoundaryInterpolation(), boundary);
  EXPECT_EQ(options.GetFVarLinearInterpolation(),
            tags.value.contains("facevaryinginterpolateboundary")
                ? Options::FVAR_LINEAR_CORNERS_ONLY  // all shapes say 1
                : Options::FVAR_LINEAR_ALL);
  EXPECT_EQ(options.GetCreasingMethod(),
            tags.value.contains("creasemethod") && tags.value.at("creasemethod") == "chaikin"
                ? Options::CREASE_CHAIKIN
                : Options::CREASE_UNIFORM);
  EXPECT_EQ(options.GetTriangleSubdivision(),
            tags.value.contains("smoothtriangles") && tags.value.at("smoothtriangles") == "smooth"
                ? Options::TRI_SUB_SMOOTH
                : Options::TRI_SUB_CATMARK);
}

std::string rowName(const ::testing::TestParamInfo<IndexRow>& info) {
  return info.param.col.at("name");
}

INSTANTIATE_TEST_SUITE_P(SharedData, ShapeIndex, ::testing::ValuesIn(allRows()), rowName);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ShapeIndex);

TEST(ShapeIndexFiles, FortyShapesAndBigGuyAreListedAndPresent) {
  OSD_CULL_REQUIRE_DATA();
  const std::vector<IndexRow> rows = allRows();
  ASSERT_EQ(rows.size(), 41u);
  int objFiles = 0;
  for (const auto& entry : fs::directory_iterator(test::dataDir() / "shapes"))
    objFiles += entry.path().extension() == ".obj";
  EXPECT_EQ(objFiles, 40);
  for (const IndexRow& row : rows) EXPECT_TRUE(fs::exists(row.file)) << row.file;
}

TEST(ShapeIndexFiles, FileNamePrefixChoosesTheSchemeAndAnOptionOverridesIt) {
  OSD_CULL_REQUIRE_DATA();
  const fs::path loopCube = test::dataDir() / "shapes" / "loop_cube.obj";
  EXPECT_EQ(adapters::loadCage(loopCube).scheme, Scheme::Loop);
  EXPECT_EQ(adapters::loadCage(test::dataDir() / "shapes" / "bilinear_cube.obj").scheme,
            Scheme::Bilinear);
  EXPECT_EQ(adapters::loadCage(test::dataDir() / "characters" / "bigguy.obj").scheme,
            Scheme::CatmullClark);
  adapters::LoadOptions bilinear;
  bilinear.scheme = Scheme::Bilinear;
  EXPECT_EQ(adapters::loadCage(loopCube, bilinear).scheme, Scheme::Bilinear);
}

TEST(ShapeIndexFiles, LeftHandedOptionReversesWindingKeepingTheFirstVertex) {
  OSD_CULL_REQUIRE_DATA();
  const fs::path file = test::dataDir() / "shapes" / "catmark_lefthanded.obj";
  const CageMesh right = adapters::loadCage(file);
  adapters::LoadOptions options;
  options.leftHanded = true;
  const CageMesh left = adapters::loadCage(file, options);
  ASSERT_EQ(left.faceVertices.size(), right.faceVertices.size());
  // Face 0: (a b c d) becomes (a d c b).
  EXPECT_EQ(left.faceVertices[0], right.faceVertices[0]);
  EXPECT_EQ(left.faceVertices[1], right.faceVertices[3]);
  EXPECT_EQ(left.faceVertices[3], right.faceVertices[1]);
  EXPECT_TRUE(summarize(*makeTopologyRefiner(left)).closed);
}

}  // namespace
}  // namespace osd_cull
