// OFF (own reader), PLY, STL and binary OFF (OpenMesh's readers) on small files written to
// temporary folders.
#include "adapters/load_mesh.h"
#include "osd_cull/error.h"
#include "osd_cull/patch/refiner.h"
#include "support/temp_dir.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;
using adapters::loadCage;

// A temp folder whose name says which suite wrote it.
struct TempDir : test::TempDir {
  TempDir() : test::TempDir("osd_cull_om_") {}
};

// Little helpers to build binary files byte by byte.
struct Bytes {
  std::string data;
  Bytes& text(const std::string& s) {
    data += s;
    return *this;
  }
  Bytes& u8(uint8_t v) {
    data += static_cast<char>(v);
    return *this;
  }
  Bytes& u16le(uint16_t v) { return u8(v & 0xff).u8(v >> 8); }
  Bytes& u32le(uint32_t v) { return u16le(v & 0xffff).u16le(v >> 16); }
  Bytes& u32be(uint32_t v) {
    return u8(v >> 24).u8((v >> 16) & 0xff).u8((v >> 8) & 0xff).u8(v & 0xff);
  }
  Bytes& f32le(float f) { return u32le(std::bit_cast<uint32_t>(f)); }
  Bytes& f32be(float f) { return u32be(std::bit_cast<uint32_t>(f)); }
};

const double kCube[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                            {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
const int kCubeFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                              {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

void expectClosedCube(const CageMesh& m) {
  ASSERT_EQ(m.vertexCount(), 8);
  ASSERT_EQ(m.faceCount(), 6);
  for (int v = 0; v < 8; ++v)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(m.positions[v][k], kCube[v][k]) << "vertex " << v;
  for (int f = 0; f < 6; ++f)
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(m.faceVertices[f * 4 + k], kCubeFaces[f][k]) << "face " << f;
  const TopologySummary s = summarize(*makeTopologyRefiner(m));
  EXPECT_TRUE(s.closed);
  EXPECT_EQ(s.edges, 12);
  EXPECT_TRUE(m.notes.empty()) << ::testing::PrintToString(m.notes);
}

std::string asciiPlyCube() {
  std::string s =
      "ply\nformat ascii 1.0\ncomment a cube\nelement vertex 8\nproperty float x\nproperty float "
      "y\n"
      "property float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : kCube)
    s += std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + "\n";
  for (const auto& f : kCubeFaces)
    s += "4 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) +
         " " + std::to_string(f[3]) + "\n";
  return s;
}

TEST(OffReader, CubeWithCommentsColoursAndCountsOnTheKeywordLine) {
  TempDir dir;
  std::string off = "# exported\nCOFF 8 6 12\n";
  for (const auto& p : kCube)
    off += std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) +
           " 255 0 0 255\n";
  off += "\n";
  for (const auto& f : kCubeFaces)
    off += "4 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) +
           " " + std::to_string(f[3]) + " 0.5 0.5 0.5  # a face\r\n";
  expectClosedCube(loadCage(dir.write("cube.off", off)));
}

TEST(OffReader, KeepsNonManifoldAndRepeatedVertexFacesAsWritten) {
  TempDir dir;
  // Three triangles on the edge 0-1 (a fin) and a quad that repeats vertex 4.
  const CageMesh m = loadCage(dir.write("fin.off",
                                        "OFF\n6 4 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n2 2 2\n"
                                        "3 0 1 2\n3 1 0 3\n3 0 1 4\n4 1 5 4 4\n"));
  EXPECT_EQ(m.faceVertices, (std::vector<int>{0, 1, 2, 1, 0, 3, 0, 1, 4, 1, 5, 4, 4}));
  const TopologySummary s = summarize(*makeTopologyRefiner(m));
  EXPECT_GE(s.nonManifoldEdges, 1);
  EXPECT_EQ(s.degenerateFaces, 1);
  EXPECT_EQ(m.notes.size(), 2u) << ::testing::PrintToString(m.notes);
}

TEST(OpenMeshFormats, AsciiPlyCube) {
  TempDir dir;
  expectClosedCube(loadCage(dir.write("cube.ply", asciiPlyCube())));
}

TEST(OpenMeshFormats, BinaryLittleEndianPlyCubeWithDoubleCoordinates) {
  TempDir dir;
  Bytes b;
  b.text(
      "ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty double x\nproperty double "
      "y\n"
      "property double z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n");
  for (const auto& p : kCube)
    for (double c : p) {
      const auto bits = std::bit_cast<uint64_t>(c);
      b.u32le(static_cast<uint32_t>(bits)).u32le(static_cast<uint32_t>(bits >> 32));
    }
  for (const auto& f : kCubeFaces) {
    b.u8(4);
    for (int v : f) b.u32le(static_cast<uint32_t>(v));
  }
  expectClosedCube(loadCage(dir.write("cube.ply", b.data)));
}

TEST(OpenMeshFormats, PlyExtraPropertiesAndElementsAreSkipped) {
  TempDir dir;
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float "
      "z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float confidence\n"
      "element face 2\nproperty list uchar int vertex_indices\nproperty int flags\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
      "0 0 0 255 0 0 0.5\n1 0 0 0 255 0 0.5\n1 1 0 0 0 255 0.5\n0 1 0 9 9 9 0.25\n"
      "3 0 1 2 7\n3 0 2 3 8\n0 1\n";
  const CageMesh m = loadCage(dir.write("extra.ply", ply));
  ASSERT_EQ(m.vertexCount(), 4);
  EXPECT_EQ(m.positions[2], glm::dvec3(1, 1, 0));
  EXPECT_EQ(m.positions[3], glm::dvec3(0, 1, 0));
  EXPECT_EQ(m.faceVertices, (std::vector<int>{0, 1, 2, 0, 2, 3}));
  // OpenMesh's complaint about the element it does not know becomes one note.
  ASSERT_EQ(m.notes.size(), 1u) << ::testing::PrintToString(m.notes);
  EXPECT_EQ(m.notes[0], "OpenMesh reported: PLY header unsupported element type: edge");
}

TEST(OpenMeshFormats, BinaryBigEndianPly) {
  TempDir dir;
  Bytes b;
  b.text(
      "ply\nformat binary_big_endian 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
      "property float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n");
  for (const auto& p : kCube)
    for (double c : p) b.f32be(static_cast<float>(c));
  for (const auto& f : kCubeFaces) {
    b.u8(4);
    for (int v : f) b.u32be(static_cast<uint32_t>(v));
  }
  expectClosedCube(loadCage(dir.write("cube.ply", b.data)));
}

TEST(OpenMeshFormats, PlyNonManifoldFacesReachOpenSubdivUnsplit) {
  TempDir dir;
  // OpenMesh's own mesh kernel would refuse the third triangle on edge 0-1 and the face that
  // repeats vertex 4; the importer keeps both, as the file has them.
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float "
      "z\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n2 2 2\n3 0 1 2\n3 1 0 3\n3 0 1 4\n4 1 5 4 4\n";
  const CageMesh m = loadCage(dir.write("fin.ply", ply));
  EXPECT_EQ(m.faceVertices, (std::vector<int>{0, 1, 2, 1, 0, 3, 0, 1, 4, 1, 5, 4, 4}));
  EXPECT_EQ(m.vertexCount(), 6);
  const TopologySummary s = summarize(*makeTopologyRefiner(m));
  EXPECT_GE(s.nonManifoldEdges, 1);
  EXPECT_EQ(s.degenerateFaces, 1);
  bool noted = false;
  for (const auto& n : m.notes) noted |= n.find("more than two faces") != std::string::npos;
  EXPECT_TRUE(noted) << ::testing::PrintToString(m.notes);
}

// A tetrahedron as an STL triangle soup: 12 corners that OpenMesh merges into 4 vertices.
const float kTet[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const int kTetFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};

std::string asciiStl(const std::vector<std::array<int, 3>>& faces) {
  std::string s = "solid tet\n";
  for (const auto& f : faces) {
    s += "  facet normal 0 0 0\n    outer loop\n";
    for (int v : f)
      s += "      vertex " + std::to_string(kTet[v][0]) + " " + std::to_string(kTet[v][1]) + " " +
           std::to_string(kTet[v][2]) + "\n";
    s += "    endloop\n  endfacet\n";
  }
  return s + "endsolid tet\n";
}

std::vector<std::array<int, 3>> tetFaces() {
  std::vector<std::array<int, 3>> faces;
  for (const auto& f : kTetFaces) faces.push_back({f[0], f[1], f[2]});
  return faces;
}

void expectClosedTetrahedron(const CageMesh& m) {
  ASSERT_EQ(m.vertexCount(), 4);
  ASSERT_EQ(m.faceCount(), 4);
  // Merged corners keep the first-seen order: 0, 2, 1, 3.
  EXPECT_EQ(m.positions[1], glm::dvec3(0, 1, 0));
  const TopologySummary s = summarize(*makeTopologyRefiner(m));
  EXPECT_TRUE(s.closed);
  EXPECT_EQ(s.edges, 6);
  EXPECT_EQ(s.triangles, 4);
}

TEST(OpenMeshFormats, AsciiStlTetrahedronMergesCorners) {
  TempDir dir;
  expectClosedTetrahedron(loadCage(dir.write("tet.stl", asciiStl(tetFaces()))));
}

std::string binaryStl(const std::vector<std::array<int, 3>>& faces, float poison = 0.0f) {
  Bytes b;
  b.text(std::string(80, ' ')).u32le(static_cast<uint32_t>(faces.size()));
  for (const auto& f : faces) {
    b.f32le(0).f32le(0).f32le(0);
    for (int v : f) b.f32le(kTet[v][0] + poison).f32le(kTet[v][1]).f32le(kTet[v][2]);
    b.u16le(0);
  }
  return b.data;
}

TEST(OpenMeshFormats, BinaryStlTetrahedron) {
  TempDir dir;
  const std::string stl = binaryStl(tetFaces());
  ASSERT_EQ(stl.size(), 84u + 4 * 50);
  expectClosedTetrahedron(loadCage(dir.write("tet.STL", stl)));
}

TEST(OpenMeshFormats, StlTriangleThatCollapsesIsDroppedWithANote) {
  TempDir dir;
  auto faces = tetFaces();
  faces.push_back({0, 1, 1});
  const CageMesh m = loadCage(dir.write("tet.stl", asciiStl(faces)));
  EXPECT_EQ(m.faceCount(), 4);
  ASSERT_FALSE(m.notes.empty());
  EXPECT_NE(m.notes[0].find("1 STL triangle(s) collapsed"), std::string::npos) << m.notes[0];
}

std::string binaryOffCube(bool bigEndian) {
  Bytes b;
  auto word = [&](uint32_t v) { bigEndian ? b.u32be(v) : b.u32le(v); };
  b.text("OFF BINARY\n");
  word(8), word(6), word(0);
  for (const auto& p : kCube)
    for (double c : p) word(std::bit_cast<uint32_t>(static_cast<float>(c)));
  for (const auto& f : kCubeFaces) {
    word(4);
    for (int v : f) word(static_cast<uint32_t>(v));
    word(0);  // no colour components
  }
  return b.data;
}

TEST(OffReader, BinaryOffCubeInSpecificationByteOrder) {
  TempDir dir;
  expectClosedCube(loadCage(dir.write("cube.off", binaryOffCube(/*bigEndian=*/true))));
}

TEST(OffReader, LittleEndianBinaryOffIsRecognisedAndNoted) {
  TempDir dir;
  const CageMesh m = loadCage(dir.write("cube.off", binaryOffCube(/*bigEndian=*/false)));
  ASSERT_EQ(m.faceCount(), 6);
  EXPECT_EQ(m.positions[6], glm::dvec3(1, 1, 1));
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_NE(m.notes[0].find("little-endian"), std::string::npos);
}

TEST(OpenMeshFormats, SchemeComesFromTheFileNameForEveryFormat) {
  TempDir dir;
  EXPECT_EQ(loadCage(dir.write("loop_tet.stl", asciiStl(tetFaces()))).scheme, Scheme::Loop);
  EXPECT_EQ(loadCage(dir.write("bilinear_cube.ply", asciiPlyCube())).scheme, Scheme::Bilinear);
  // Loop needs triangles: a quad PLY named loop_ is refused with the face named.
  try {
    loadCage(dir.write("loop_cube.ply", asciiPlyCube()));
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Loop scheme needs triangles"), std::string::npos)
        << e.what();
  }
}

TEST(OpenMeshFormats, ExtensionsListsWhatThisBuildReads) {
  const auto ext = adapters::cageFileExtensions();
  EXPECT_NE(std::find(ext.begin(), ext.end(), ".obj"), ext.end());
  EXPECT_NE(std::find(ext.begin(), ext.end(), ".off"), ext.end());
  EXPECT_NE(std::find(ext.begin(), ext.end(), ".ply"), ext.end());
  EXPECT_NE(std::find(ext.begin(), ext.end(), ".stl"), ext.end());
  EXPECT_TRUE(adapters::isBezierPatchFile("x/teapot.BPT"));
  EXPECT_FALSE(adapters::isBezierPatchFile("x/teapot.obj"));
}

}  // namespace
}  // namespace osd_cull
