// Bad input gives an osd_cull::Error naming the file, the line (where the format has lines)
// and the problem; nothing crashes, hangs or allocates what a header claims.
#include "adapters/load_mesh.h"
#include "osd_cull/error.h"
#include "osd_cull/patch/refiner.h"
#include "support/load_errors.h"
#include "support/temp_dir.h"

#include <gtest/gtest.h>

#include <bit>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <random>
#include <string>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;
using adapters::loadBezierPatches;
using adapters::loadCage;

// A temp folder whose name says which suite wrote it.
struct TempDir : test::TempDir {
  TempDir() : test::TempDir("osd_cull_bad_") {}
};

using test::expectLoadError;
using test::loadError;

// Short names: most tests here are lists of these calls.
std::string errorOf(const fs::path& file) { return loadError(file); }
void expectError(const fs::path& file, int line, std::initializer_list<const char*> phrases) {
  expectLoadError(file, line, phrases);
}

const std::string kTri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

TEST(BadInput, MissingFileAndDirectory) {
  TempDir dir;
  expectError(dir.path() / "nothing.obj", 0, {"file not found"});
  expectError(dir.path() / "nothing.bpt", 0, {"file not found"});
  fs::create_directories(dir.path() / "folder.obj");
  expectError(dir.path() / "folder.obj", 0, {"is a directory"});
  if (fs::exists("/dev/zero")) {  // a device that never ends must not be read
    fs::create_symlink("/dev/zero", dir.path() / "zero.obj");
    expectError(dir.path() / "zero.obj", 0, {"not a regular file"});
  }
}

TEST(BadInput, UnknownExtensionAndBptAsCage) {
  TempDir dir;
  expectError(dir.write("mesh.xyz", kTri), 0, {"unknown mesh format '.xyz'", ".obj"});
  const fs::path bpt = dir.write("t.bpt", "1\n");
  try {
    loadCage(bpt);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("loadBezierPatches"), std::string::npos) << e.what();
  }
}

TEST(BadInput, ObjUnreadableLines) {
  TempDir dir;
  expectError(dir.write("a.obj", kTri + "v 1 2 abc\nf 1 2 3\n"), 4, {"'abc' is not a number"});
  expectError(dir.write("b.obj", "v 1 2\nf 1 2 3\n"), 1, {"needs 3 coordinates"});
  expectError(dir.write("c.obj", kTri + "f 1 2 x\n"), 4,
              {"'x' does not start with a vertex index"});
  expectError(dir.write("d.obj", kTri + "f 1/1/1/1 2 3\n"), 4, {"not of the form"});
  expectError(dir.write("e.obj", kTri + "vt 0 zero\nf 1 2 3\n"), 4, {"not a number"});
}

TEST(BadInput, ObjIndexOutOfRangeAndZero) {
  TempDir dir;
  expectError(dir.write("a.obj", kTri + "\nf 1 2 9\n"), 5, {"vertex 9", "only 3 vertices"});
  expectError(dir.write("b.obj", kTri + "f 0 1 2\n"), 4, {"index 0", "start at 1"});
  expectError(dir.write("c.obj", kTri + "f -1 -2 -4\n"), 4, {"-4", "before the first vertex"});
  expectError(dir.write("d.obj", kTri + "f 1 2 99999999999\n"), 4, {"out of range"});
}

TEST(BadInput, ObjFaceWithFewerThanThreeVertices) {
  TempDir dir;
  expectError(dir.write("a.obj", kTri + "f 1 2\n"), 4, {"2 vertices", "at least 3"});
  expectError(dir.write("b.obj", kTri + "f\n"), 4, {"0 vertices"});
}

TEST(BadInput, NanAndInfCoordinates) {
  TempDir dir;
  expectError(dir.write("a.obj", "v 0 nan 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), 1, {"NaN or Inf"});
  expectError(dir.write("b.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n"), 2, {"NaN or Inf"});
  expectError(dir.write("c.obj", "v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n"), 3, {"NaN or Inf"});
  expectError(dir.write("d.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"), 4,
              {"NaN or Inf"});
  expectError(dir.write("e.ply",
                        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float "
                        "y\nproperty float z\n"
                        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 "
                        "0\ninf 0 0\n0 1 0\n3 0 1 2\n"),
              11, {"NaN or Inf"});
  expectError(dir.write("f.stl",
                        "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex nan 0 0\n"
                        "vertex 0 1 0\nendloop\nendfacet\nendsolid\n"),
              5, {"NaN or Inf"});
}

TEST(BadInput, DegenerateExtentIsNamedAsTheMeshsProblem) {
  TempDir dir;
  const std::string faces = "f 1 2 3\n";
  expectError(dir.write("same.obj", "v 1 2 3\nv 1 2 3\nv 1 2 3\n" + faces), 0,
              {"degenerate extent", "all 3 vertices coincide at (1, 2, 3)"});
  // 1e-320 (a subnormal double) is read as 0: the vertices coincide.
  expectError(dir.write("subnormal.obj", "v 0 0 0\nv 1e-320 0 0\nv 0 1e-320 0\n" + faces), 0,
              {"degenerate extent"});
  expectError(dir.write("tiny.obj", "v 0 0 0\nv 1e-300 0 0\nv 0 1e-300 0\n" + faces), 0,
              {"degenerate extent 1.4", "below 1e-18", "scale the mesh up"});
  expectError(dir.write("same.off", "OFF\n3 1 0\n5 5 5\n5 5 5\n5 5 5\n3 0 1 2\n"), 0,
              {"degenerate extent", "coincide"});
  std::string bpt = "1\n3 3\n";
  for (int i = 0; i < 16; ++i) bpt += "2 2 2\n";
  expectError(dir.write("same.bpt", bpt), 0, {"degenerate extent", "16 control points coincide"});
  // Small but resolvable: loads.
  EXPECT_NO_THROW(loadCage(dir.write("small.obj", "v 0 0 0\nv 1e-9 0 0\nv 0 1e-9 0\n" + faces)));
}

TEST(BadInput, EmptyMeshes) {
  TempDir dir;
  expectError(dir.write("a.obj", ""), 0, {"no vertices", "empty"});
  expectError(dir.write("b.obj", "# only a comment\n\n"), 0, {"no vertices"});
  expectError(dir.write("c.obj", kTri), 0, {"no faces", "empty"});
  expectError(dir.write("d.off", ""), 0, {"empty"});
  expectError(dir.write("e.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"), 2, {"0 faces", "empty"});
  expectError(dir.write("f.stl", "solid x\nendsolid x\n"), 0, {"no facets", "empty"});
  expectError(
      dir.write(
          "g.ply",
          "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
          "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"),
      0, {"no vertices"});
  expectError(dir.write("h.bpt", "0\n"), 1, {"no patches"});
}

TEST(BadInput, SharpnessThatIsNotANumber) {
  TempDir dir;
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
  expectError(dir.write("a.obj", quad + "t crease 2/1/0 0 1 sharp\n"), 6,
              {"'sharp', not a number"});
  expectError(dir.write("b.obj", quad + "t crease 2/1/0 0 1 nan\n"), 6, {"not a number"});
  expectError(dir.write("c.obj", quad + "t corner 1/1/0 0 inf\n"), 6, {"not a finite number"});
  expectError(dir.write("d.obj", quad + "t crease 2/1/0 0 x 1\n"), 6, {"'x', not an integer"});
}

TEST(BadInput, MalformedTags) {
  TempDir dir;
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
  expectError(dir.write("a.obj", quad + "t crease 2/1/0 0 1\n"), 6,
              {"declares 2 integer, 1 float", "has 2"});
  expectError(dir.write("b.obj", quad + "t crease two/1/0 0 1 1\n"), 6, {"ints/floats/strings"});
  expectError(dir.write("c.obj", quad + "t crease\n"), 6, {"lacks its argument counts"});
  expectError(dir.write("d.obj", quad + "t crease 1/1/0 0 1\n"), 6, {"at least 2 vertex indices"});
  expectError(dir.write("e.obj", quad + "t crease 3/3/0 0 1 2 1 1 1\n"), 6,
              {"1 sharpness or one per edge (2)"});
  expectError(dir.write("f.obj", quad + "t interpolateboundary 1/0/0 7\n"), 6, {"value 7"});
  expectError(dir.write("g.obj", quad + "t creasemethod 0/0/1 sharpest\n"), 6, {"'sharpest'"});
  expectError(dir.write("h.obj", quad + "t crease 2/1/0 0 2 1\n"), 6,
              {"vertices 0 and 2 are not joined by an edge"});
  expectError(dir.write("i.obj", quad + "\nt corner 1/1/0 4 1\n"), 7,
              {"vertex 4, out of range [0, 4)"});
  expectError(dir.write("j.obj", quad + "t hole 1/0/0 1\n"), 6, {"face 1, out of range [0, 1)"});
  expectError(dir.write("k.obj", quad + "t crease 2/1/0 -1 0 1\n"), 6, {"vertex -1"});
  expectError(dir.write("l.obj", quad + "t crease 2000000000/0/0 1\n"), 6,
              {"declares 2000000000 integer"});
}

TEST(BadInput, LoopSchemeFaceThatIsNotATriangle) {
  TempDir dir;
  expectError(dir.write("loop_quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"), 5,
              {"Loop scheme needs triangles"});
}

TEST(BadInput, OffProblemsNameTheirLine) {
  TempDir dir;
  expectError(dir.write("a.off", "MESH\n3 1 0\n"), 1, {"expected the OFF header keyword"});
  expectError(dir.write("b.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"), 6,
              {"index 3 is out of range [0, 3)"});
  expectError(dir.write("c.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n"), 6,
              {"2 vertices", "at least 3"});
  expectError(dir.write("d.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n"), 6,
              {"declares 4 vertices"});
  expectError(dir.write("e.off", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n"), 4,
              {"needs 3 coordinates"});
  expectError(dir.write("f.off", "OFF\nthree 1 0\n"), 2, {"'three'"});
  expectError(dir.write("g.off", "4OFF\n3 1 0\n"), 1, {"higher-dimensional"});
}

const std::string kPlyTriangleHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
    "z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";

std::string binaryPlyTriangle(int32_t lastIndex, bool cut) {
  std::string b =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  auto word = [&](uint32_t v) {
    for (int k = 0; k < 4; ++k) b += static_cast<char>((v >> (8 * k)) & 0xff);
  };
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) word(std::bit_cast<uint32_t>(c));
  b += '\x03';
  word(0), word(1), word(static_cast<uint32_t>(lastIndex));
  if (cut) b.resize(b.size() - 3);
  return b;
}

TEST(BadInput, PlyProblemsNameTheirLineOrByte) {
  TempDir dir;
  expectError(dir.write("a.ply", kPlyTriangleHeader + "3 0 1 3\n"), 13,
              {"face 0 of 1 uses vertex index 3, out of range [0, 3)"});
  expectError(dir.write("b.ply", kPlyTriangleHeader + "2 0 1\n"), 13, {"2 vertices", "at least 3"});
  expectError(dir.write("c.ply", kPlyTriangleHeader + "3 0 1 1.5\n"), 13,
              {"'1.5' is not an integer"});
  expectError(dir.write("d.ply", kPlyTriangleHeader + "3 0 1\n"), 13,
              {"ends inside face 0 of 1", "truncated"});
  expectError(dir.write("e.ply", binaryPlyTriangle(7, false)), 0, {"vertex index 7", "at byte"});
  expectError(dir.write("f.ply", binaryPlyTriangle(2, true)), 0, {"ends at byte", "truncated"});
  expectError(
      dir.write("g.ply",
                "ply\nformat ascii 2.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                "end_header\n"),
      0, {"'vertex' elements", "bytes after the header"});
  expectError(
      dir.write("h.ply",
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0\n1 0\n0 "
                "1\n3 0 1 2\n"),
      0, {"lacks x, y or z"});
  expectError(
      dir.write("i.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty quaternion x\n"), 4,
      {"unknown"});
  expectError(dir.write("j.ply", "ply\nformat ebcdic 1.0\nend_header\n"), 2,
              {"unknown PLY format 'ebcdic'"});
}

TEST(BadInput, StlProblemsNameTheirLine) {
  TempDir dir;
  const std::string head = "solid s\nfacet normal 0 0 1\nouter loop\n";
  expectError(
      dir.write("a.stl",
                head + "vertex 0 0 0\nvertex 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n"),
      5, {"expected 'vertex x y z' (corner 2 of 3)"});
  expectError(
      dir.write("b.stl", head + "vertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n"), 6,
      {"corner 3 of 3", "'endloop'"});
  expectError(dir.write("c.stl", head + "vertex 0 0 0\nvertex 1 0 0\nvertex 0 one 0\nendloop\n"), 6,
              {"'one' is not a number"});
  expectError(dir.write("d.stl", "solid s\nvertex 0 0 0\nendsolid\n"), 2,
              {"outside an 'outer loop'"});
  expectError(dir.write("e.stl", head + "vertex 0 0 0\n"), 0, {"ends inside a facet", "truncated"});
  // Binary STL with a NaN corner.
  std::string stl(80, ' ');
  stl += std::string("\x01\0\0\0", 4) + std::string(50, '\0');
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(stl.data() + 84 + 12 + 4, &nan, 4);
  expectError(dir.write("f.stl", stl), 0, {"triangle 0 has a NaN or Inf coordinate"});
}

TEST(BadInput, TruncatedFiles) {
  TempDir dir;
  expectError(dir.write("a.off", "OFF\n8 6 12\n0 0 0\n1 0 0\n"), 2, {"only 2 lines follow"});
  expectError(dir.write("b.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n\n"), 0,
              {"1 of 2 faces", "truncated"});
  expectError(dir.write("c.obj", kTri + "f 1 2"), 4, {"2 vertices"});
  expectError(dir.write("d.bpt", "1\n3 3\n0 0 0\n"), 1, {"1 patches", "lines follow"});
  std::string bpt = "1\n3 3\n";
  for (int i = 0; i < 15; ++i) bpt += "0 0 0\n";
  expectError(dir.write("e.bpt", bpt + "\n\n"), 0, {"after 15 of 16 points", "truncated"});
  expectError(dir.write("f.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"), 0, {"end_header"});
  // Binary STL whose last triangle is cut off.
  std::string stl(80, ' ');
  stl += std::string("\x02\x00\x00\x00", 4) + std::string(50 + 30, '\0');
  expectError(dir.write("g.stl", stl), 0, {"declares 2 triangles", "file has 164"});
}

TEST(BadInput, HugeHeaderCountsAreRefusedQuickly) {
  TempDir dir;
  const auto start = std::chrono::steady_clock::now();
  expectError(dir.write("a.off", "OFF\n1000000000000 1 0\n0 0 0\n"), 2, {"too large"});
  expectError(dir.write("b.off", "OFF\n2000000000 2000000000 0\n0 0 0\n"), 2, {"lines follow"});
  expectError(dir.write("c.bpt", "1000000000000\n3 3\n"), 1, {"1000000000000 patches"});
  expectError(dir.write("d.ply",
                        "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\n"
                        "property float x\nproperty float y\nproperty float z\nelement face 1\n"
                        "property list uchar int vertex_indices\nend_header\n" +
                            std::string(64, '\0')),
              3, {"'1000000000000' is not an integer in [0, 2^32)"});
  expectError(
      dir.write(
          "e.ply",
          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
          "property float z\nelement face 4000000000\nproperty list uchar int vertex_indices\n"
          "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
      0, {"4000000000 'face' elements"});
  std::string stl(80, ' ');
  stl += std::string("\xff\xff\xff\xff", 4) + std::string(50, '\0');
  expectError(dir.write("f.stl", stl), 0, {"declares 4294967295 triangles"});
  std::string off = "OFF BINARY\n";
  off += std::string("\x7f\xff\xff\xff\x7f\xff\xff\xff\0\0\0\0", 12) + std::string(40, '\0');
  expectError(dir.write("g.off", off), 0, {"2147483647 vertices", "do not fit"});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 2.0);
}

TEST(BadInput, BinaryGarbageInEveryFormat) {
  TempDir dir;
  std::mt19937 random(12345);
  std::string garbage(4096, '\0');
  for (char& c : garbage) c = static_cast<char>(random() & 0xff);
  expectError(dir.write("g.obj", garbage), 1, {"binary data"});
  expectError(dir.write("g.off", garbage), 1, {"binary data"});
  expectError(dir.write("g.bpt", garbage), 1, {"binary data"});
  expectError(dir.write("g.ply", garbage), 1, {"not a PLY file"});
  expectError(dir.write("g.stl", garbage), 0, {"neither ASCII STL"});
  // Valid headers followed by garbage.
  expectError(dir.write("h.obj", kTri + garbage), 4, {"binary data"});
  expectError(dir.write("h.off", "OFF\n3 1 0\n" + garbage), 3, {"binary data"});
  expectError(dir.write("h.stl", "solid x\n" + garbage), 2, {"binary data"});
  const std::string plyHeader =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_FALSE(errorOf(dir.write("h.ply", plyHeader + garbage)).empty());
  const std::string binaryPlyHeader =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  EXPECT_FALSE(errorOf(dir.write("i.ply", binaryPlyHeader + garbage)).empty());
}

// Every prefix of a valid file either loads or gives an osd_cull::Error: no crash, no other
// exception type, no hang.
void everyPrefixLoadsOrThrows(const TempDir& dir, const std::string& name,
                              const std::string& bytes) {
  for (size_t n = 0; n <= bytes.size(); ++n) {
    const fs::path file = dir.write(name, bytes.substr(0, n));
    try {
      if (adapters::isBezierPatchFile(file))
        loadBezierPatches(file);
      else
        loadCage(file);
    } catch (const Error&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << name << " cut at " << n << " bytes: " << e.what();
    }
  }
}

TEST(BadInput, EveryTruncationLoadsOrGivesAnError) {
  TempDir dir;
  everyPrefixLoadsOrThrows(dir, "q.obj",
                           "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nt corner 1/1/0 0 2.0\n");
  everyPrefixLoadsOrThrows(dir, "q.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  everyPrefixLoadsOrThrows(
      dir, "q.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  std::string binaryPly =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) {
    const auto bits = std::bit_cast<uint32_t>(c);
    for (int k = 0; k < 4; ++k) binaryPly += static_cast<char>((bits >> (8 * k)) & 0xff);
  }
  binaryPly += std::string("\x03\0\0\0\0\x01\0\0\0\x02\0\0\0", 13);
  everyPrefixLoadsOrThrows(dir, "b.ply", binaryPly);
  everyPrefixLoadsOrThrows(dir, "q.stl",
                           "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                           "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n");
  std::string bpt = "1\n3 3\n";
  for (int i = 0; i < 16; ++i) bpt += std::to_string(i % 4) + " " + std::to_string(i / 4) + " 0\n";
  everyPrefixLoadsOrThrows(dir, "q.bpt", bpt);
}

// Random byte edits of small valid files: each result loads (and then OpenSubdiv builds it
// or refuses it with an Error) or gives an Error. Deterministic seed; about 2000 cases.
TEST(BadInput, RandomByteEditsLoadOrGiveAnError) {
  TempDir dir;
  std::string bpt = "1\n3 3\n";
  for (int i = 0; i < 16; ++i) bpt += std::to_string(i % 4) + " " + std::to_string(i / 4) + " 0\n";
  const std::pair<const char*, std::string> files[] = {
      {"m.obj",
       "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nf 1 2 3 4\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 "
       "5\n"
       "t crease 2/1/0 0 1 2.5\nt corner 1/1/0 4 1\nt hole 1/0/0 1\nt interpolateboundary 1/0/0 "
       "1\n"},
      {"m.off",
       "OFF\n5 5 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n4 0 1 2 3\n3 0 1 4\n3 1 2 4\n"
       "3 2 3 4\n3 3 0 4\n"},
      {"m.ply",
       "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
       "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
       "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n"},
      {"m.stl",
       "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
       "endloop\nendfacet\nendsolid t\n"},
      {"m.bpt", bpt},
  };
  std::mt19937 random(2024);
  const char alphabet[] = "0123456789 -+.e/\n#\tnafvt\\";
  int loaded = 0;
  for (const auto& [name, text] : files) {
    for (int trial = 0; trial < 400; ++trial) {
      std::string edited = text;
      const int edits = 1 + static_cast<int>(random() % 3);
      for (int e = 0; e < edits; ++e) {
        const size_t at = random() % edited.size();
        const char c = random() % 4 == 0 ? static_cast<char>(random() & 0xff)
                                         : alphabet[random() % (sizeof alphabet - 1)];
        switch (random() % 3) {
          case 0:
            edited[at] = c;
            break;
          case 1:
            edited.insert(edited.begin() + static_cast<std::ptrdiff_t>(at), c);
            break;
          default:
            edited.erase(at, 1);
            break;
        }
      }
      const fs::path file = dir.write(name, edited);
      try {
        if (adapters::isBezierPatchFile(file)) {
          loadBezierPatches(file);
        } else {
          makeTopologyRefiner(loadCage(file));
        }
        ++loaded;
      } catch (const Error&) {
      } catch (const std::exception& e) {
        ADD_FAILURE() << name << " edit " << trial << ": " << e.what() << "\n" << edited;
      }
    }
  }
  EXPECT_GT(loaded, 100);  // many edits (inside numbers, comments) leave a valid file
}

TEST(BadInput, BptProblemsNameTheirLine) {
  TempDir dir;
  std::string points;
  for (int i = 0; i < 16; ++i) points += "0 0 0\n";
  expectError(dir.write("a.bpt", "1\n3 2\n" + points), 2, {"'3 3'", "bicubic"});
  expectError(dir.write("b.bpt", "one\n3 3\n" + points), 1, {"patch count"});
  std::string bad = points;
  bad.replace(6, 5, "0 x 0");
  expectError(dir.write("c.bpt", "1\n3 3\n" + bad), 4, {"'x' is not a number"});
  bad = points;
  bad.replace(6, 5, "0 nan");
  expectError(dir.write("d.bpt", "1\n3 3\n" + bad), 4, {"expected a point"});
  bad = points;
  bad.replace(6, 5, "0 0 inf");
  expectError(dir.write("e.bpt", "1\n3 3\n" + bad + "\n"), 4, {"NaN or Inf"});
  expectError(dir.write("f.bpt", "1\n3 3\n" + points + "3 3\n"), 19,
              {"content after the last of 1 patches"});
}

}  // namespace
}  // namespace osd_cull
