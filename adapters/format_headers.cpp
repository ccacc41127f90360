#include "adapters/format_headers.h"

#include "adapters/text_input.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

namespace osd_cull::adapters::detail {
namespace {

// Bytes of a PLY scalar type; 0 for an unknown name.
int plyTypeSize(std::string_view t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

struct PlyElement {
  std::string name;
  int64_t count = 0;
  int64_t minBytes = 0;  // smallest encoding of one element
  bool hasX = false, hasY = false, hasZ = false, hasList = false;
};

uint32_t readU32(std::string_view bytes, size_t at, bool bigEndian) {
  unsigned char b[4];
  std::memcpy(b, bytes.data() + at, 4);
  return bigEndian ? (uint32_t{b[0]} << 24 | uint32_t{b[1]} << 16 | uint32_t{b[2]} << 8 | b[3])
                   : (uint32_t{b[3]} << 24 | uint32_t{b[2]} << 16 | uint32_t{b[1]} << 8 | b[0]);
}

}  // namespace

PlyHeader checkPlyHeader(std::string_view bytes, const std::string& file) {
  if (!bytes.starts_with("ply\n") && !bytes.starts_with("ply\r\n"))
    fail(file, 1, "not a PLY file (it does not start with the line 'ply')");
  const size_t end = bytes.find("end_header");
  if (end == std::string_view::npos) fail(file, 0, "the PLY header has no 'end_header' line (truncated file?)");
  size_t dataStart = bytes.find('\n', end);
  dataStart = dataStart == std::string_view::npos ? bytes.size() : dataStart + 1;

  LineReader lines(bytes.substr(0, dataStart), file, /*joinContinuations=*/false);
  lines.next();  // "ply"
  PlyHeader header;
  bool haveFormat = false;
  std::vector<PlyElement> elements;
  while (lines.next()) {
    const auto tokens = splitTokens(lines.line());
    if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info") continue;
    if (tokens[0] == "end_header") break;
    if (tokens[0] == "format") {
      if (tokens.size() < 2) lines.fail("'format' needs a value");
      if (tokens[1] == "ascii") header.ascii = true;
      else if (tokens[1] == "binary_little_endian" || tokens[1] == "binary_big_endian") header.ascii = false;
      else lines.fail("unknown PLY format " + quote(tokens[1]));
      haveFormat = true;
    } else if (tokens[0] == "element") {
      if (tokens.size() < 3) lines.fail("'element' needs a name and a count");
      const auto n = parseInt(tokens[2]);
      if (!n || *n < 0) lines.fail("element count " + quote(tokens[2]) + " is not a non-negative integer");
      elements.push_back({std::string(tokens[1]), *n});
    } else if (tokens[0] == "property") {
      if (elements.empty()) lines.fail("'property' before any 'element'");
      PlyElement& e = elements.back();
      const bool list = tokens.size() >= 2 && tokens[1] == "list";
      if (tokens.size() != (list ? 5u : 3u))
        lines.fail(list ? "expected 'property list COUNT-TYPE ITEM-TYPE NAME'" : "expected 'property TYPE NAME'");
      const int size = plyTypeSize(tokens[1 + (list ? 1 : 0)]);
      if (size == 0 || (list && plyTypeSize(tokens[3]) == 0))
        lines.fail("unknown PLY property type in " + quote(lines.line()));
      e.minBytes += header.ascii ? 2 : size;  // ascii: at least one digit and a separator
      const std::string_view name = tokens.back();
      e.hasX |= name == "x";
      e.hasY |= name == "y";
      e.hasZ |= name == "z";
      e.hasList |= list;
    } else {
      lines.fail("unknown PLY header keyword " + quote(tokens[0]));
    }
  }
  if (!haveFormat) fail(file, 0, "the PLY header has no 'format' line");

  const auto available = static_cast<int64_t>(bytes.size() - dataStart);
  int64_t needed = 0;
  bool haveVertex = false, haveFace = false;
  for (const PlyElement& e : elements) {
    const int64_t perItem = std::max<int64_t>(e.minBytes, 1);
    if (e.count > (available - needed) / perItem)
      fail(file, 0, "the header declares " + std::to_string(e.count) + " '" + e.name + "' elements, more than the " +
                        std::to_string(available) + " bytes after the header can hold (truncated file or wrong header)");
    needed += e.count * perItem;
    if (e.name == "vertex") {
      if (!(e.hasX && e.hasY && e.hasZ)) fail(file, 0, "the 'vertex' element lacks x, y or z");
      header.vertices = e.count;
      haveVertex = true;
    } else if (e.name == "face") {
      if (!e.hasList) fail(file, 0, "the 'face' element has no vertex index list");
      header.faces = e.count;
      haveFace = true;
    }
  }
  if (!haveVertex || header.vertices == 0) fail(file, 0, "the PLY file has no vertices: the mesh is empty");
  if (!haveFace || header.faces == 0) fail(file, 0, "the PLY file has no faces: the mesh is empty");
  return header;
}

StlInfo checkStl(std::string_view bytes, const std::string& file) {
  StlInfo info;
  if (bytes.size() >= 84) {
    const uint32_t n = readU32(bytes, 80, /*bigEndian=*/false);
    if (84 + 50 * static_cast<uint64_t>(n) == bytes.size()) {
      info.binary = true;
      info.triangles = n;
      for (uint32_t t = 0; t < n; ++t) {
        for (int k = 0; k < 12; ++k) {  // normal and three corners
          const auto value = std::bit_cast<float>(readU32(bytes, 84 + 50 * size_t{t} + 4 * static_cast<size_t>(k), false));
          if (k >= 3 && !std::isfinite(value))
            fail(file, 0, "binary STL triangle " + std::to_string(t) + " has a NaN or Inf coordinate");
        }
      }
      return info;
    }
  }
  const size_t first = bytes.find_first_not_of(" \t\r\n");
  if (first != std::string_view::npos && bytes.substr(first).starts_with("solid")) {
    LineReader lines(bytes, file, /*joinContinuations=*/false);
    while (lines.next()) {
      const auto tokens = splitTokens(lines.line());
      if (!tokens.empty() && tokens[0] == "facet") ++info.triangles;
    }
    if (info.triangles == 0) fail(file, 0, "the ASCII STL file has no facets: the mesh is empty");
    return info;
  }
  if (bytes.size() < 84) fail(file, 0, "neither ASCII STL (no 'solid') nor binary STL (shorter than the 84-byte header)");
  const uint32_t n = readU32(bytes, 80, false);
  fail(file, 0, "neither ASCII STL (no 'solid') nor binary STL: the header declares " + std::to_string(n) +
                    " triangles, " + std::to_string(84 + 50 * static_cast<uint64_t>(n)) + " bytes, but the file has " +
                    std::to_string(bytes.size()) + " (truncated file or wrong header)");
}

}  // namespace osd_cull::adapters::detail
