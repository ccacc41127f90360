// checkPly(): the PLY header and a walk over every element (see format_headers.h).
#include "adapters/format_headers.h"
#include "adapters/text_input.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

namespace osd_cull::adapters::detail {
namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64, Unknown };

PlyType plyType(std::string_view t) {
  if (t == "char" || t == "int8") return PlyType::Int8;
  if (t == "uchar" || t == "uint8") return PlyType::UInt8;
  if (t == "short" || t == "int16") return PlyType::Int16;
  if (t == "ushort" || t == "uint16") return PlyType::UInt16;
  if (t == "int" || t == "int32") return PlyType::Int32;
  if (t == "uint" || t == "uint32") return PlyType::UInt32;
  if (t == "float" || t == "float32") return PlyType::Float32;
  if (t == "double" || t == "float64") return PlyType::Float64;
  return PlyType::Unknown;
}

int byteSize(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Float64:
      return 8;
    default:
      return 4;
  }
}

bool isFloat(PlyType t) { return t == PlyType::Float32 || t == PlyType::Float64; }

// The range of an integer type.
std::pair<int64_t, int64_t> intRange(PlyType t) {
  switch (t) {
    case PlyType::Int8:
      return {-128, 127};
    case PlyType::UInt8:
      return {0, 255};
    case PlyType::Int16:
      return {-32768, 32767};
    case PlyType::UInt16:
      return {0, 65535};
    case PlyType::Int32:
      return {std::numeric_limits<int32_t>::min(), std::numeric_limits<int32_t>::max()};
    default:
      return {0, std::numeric_limits<uint32_t>::max()};
  }
}

struct PlyProperty {
  std::string name;
  bool list = false;
  PlyType countType = PlyType::Unknown;
  PlyType type = PlyType::Unknown;
};

struct PlyElement {
  std::string name;
  int64_t count = 0;
  std::vector<PlyProperty> properties;
  bool isFaceIndexList(const PlyProperty& p) const {
    return name == "face" && p.list && (p.name == "vertex_indices" || p.name == "vertex_index");
  }
};

struct Header {
  PlyInfo info;
  bool bigEndian = false;
  size_t dataStart = 0;
  int lines = 0;  // header lines, including end_header
  std::vector<PlyElement> elements;
};

// The header grammar OpenMesh's PLYReader::can_u_read reads with `istream >>` (a token that
// fails to parse leaves the stream failed and its loop spinning, so every token is checked):
// "format TYPE VERSION" right after "ply"; "element NAME COUNT" with COUNT an unsigned int;
// list count types uint8, uchar, uint16 or int; in "face", vertex_indices first (OpenMesh
// drops properties declared before it, and would read their values as indices).
// A 'property' line of the header: appended to the last element.
void parseProperty(LineReader& lines, const std::vector<std::string_view>& tokens, Header& h) {
  if (h.elements.empty()) lines.fail("'property' before any 'element'");
  PlyElement& e = h.elements.back();
  PlyProperty p;
  p.list = tokens.size() >= 2 && tokens[1] == "list";
  if (tokens.size() != (p.list ? 5u : 3u))
    lines.fail(p.list ? "expected 'property list COUNT-TYPE ITEM-TYPE NAME'"
                      : "expected 'property TYPE NAME'");
  p.countType = p.list ? plyType(tokens[2]) : PlyType::Unknown;
  p.type = plyType(tokens[p.list ? 3 : 1]);
  p.name = std::string(tokens.back());
  if (p.type == PlyType::Unknown) lines.fail("unknown PLY property type in " + quote(lines.line()));
  if (p.list) {
    const std::string_view ct = tokens[2];
    if (ct != "uchar" && ct != "uint8" && ct != "uint16" && ct != "int")
      lines.fail("list count type " + quote(ct) +
                 " is not supported (uchar, uint8, uint16 or int)");
    if (e.name != "face") lines.fail("list properties are only supported in the 'face' element");
    if (e.isFaceIndexList(p) && !e.properties.empty())
      lines.fail("'" + p.name + "' must be the first property of 'face'");
  }
  e.properties.push_back(p);
}

// Counts must fit the bytes that follow (an ASCII value takes at least two bytes), so a
// header claiming 10^12 elements is refused before anything is read; the vertex and face
// elements are there and not empty.
void checkCounts(std::string_view bytes, const std::string& file, Header& h) {
  const auto available = static_cast<int64_t>(bytes.size() - h.dataStart);
  int64_t needed = 0;
  bool haveVertex = false, haveFace = false;
  for (const PlyElement& e : h.elements) {
    int64_t perItem = 0;
    bool x = false, y = false, z = false, list = false;
    for (const PlyProperty& p : e.properties) {
      perItem += h.info.ascii ? 2 : byteSize(p.list ? p.countType : p.type);
      x |= p.name == "x", y |= p.name == "y", z |= p.name == "z";
      list |= e.isFaceIndexList(p);
    }
    perItem = std::max<int64_t>(perItem, 1);
    if (e.count > (available - needed) / perItem)
      fail(file, 0,
           "the header declares " + std::to_string(e.count) + " '" + e.name +
               "' elements, more than the " + std::to_string(available) +
               " bytes after the header can hold (truncated file or wrong header)");
    needed += e.count * perItem;
    if (e.name == "vertex") {
      if (!(x && y && z)) fail(file, 0, "the 'vertex' element lacks x, y or z");
      h.info.vertices = e.count;
      haveVertex = true;
    } else if (e.name == "face") {
      if (!list) fail(file, 0, "the 'face' element has no 'vertex_indices' list");
      h.info.faces = e.count;
      haveFace = true;
    }
  }
  if (!haveVertex || h.info.vertices == 0)
    fail(file, 0, "the PLY file has no vertices: the mesh is empty");
  if (!haveFace || h.info.faces == 0) fail(file, 0, "the PLY file has no faces: the mesh is empty");
}

Header parseHeader(std::string_view bytes, const std::string& file) {
  if (!bytes.starts_with("ply\n") && !bytes.starts_with("ply\r\n"))
    fail(file, 1, "not a PLY file (it does not start with the line 'ply')");
  Header h;
  bool haveFormat = false, ended = false;
  LineReader lines(bytes, file, /*joinContinuations=*/false);
  lines.next();  // "ply"
  while (!ended && lines.next()) {
    const auto tokens = splitTokens(lines.line());
    if (tokens.empty()) continue;
    if (!haveFormat && tokens[0] != "format")
      lines.fail("expected 'format TYPE VERSION' right after 'ply', found " + quote(tokens[0]));
    if (tokens[0] == "comment") continue;
    if (tokens[0] == "obj_info") {
      for (std::string_view t : tokens)
        if (t == "comment" || t == "element" || t == "property" || t == "end_header" ||
            t == "format")
          lines.fail("'obj_info' text containing the header keyword " + quote(t));
      continue;
    }
    if (tokens[0] == "end_header") {
      if (tokens.size() != 1) lines.fail("text after 'end_header'");
      ended = true;
    } else if (tokens[0] == "format") {
      if (haveFormat) lines.fail("a second 'format' line");
      if (tokens.size() != 3 || !parseDouble(tokens[2]))
        lines.fail("expected 'format TYPE VERSION' (e.g. 'format ascii 1.0')");
      if (tokens[1] == "ascii")
        h.info.ascii = true;
      else if (tokens[1] == "binary_little_endian")
        h.info.ascii = false;
      else if (tokens[1] == "binary_big_endian")
        h.info.ascii = false, h.bigEndian = true;
      else
        lines.fail("unknown PLY format " + quote(tokens[1]));
      haveFormat = true;
    } else if (tokens[0] == "element") {
      if (tokens.size() != 3) lines.fail("expected 'element NAME COUNT'");
      const auto n = parseInt(tokens[2]);
      if (!n || *n < 0 || *n > std::numeric_limits<uint32_t>::max())
        lines.fail("element count " + quote(tokens[2]) + " is not an integer in [0, 2^32)");
      h.elements.push_back({std::string(tokens[1]), *n, {}});
    } else if (tokens[0] == "property") {
      parseProperty(lines, tokens, h);
    } else {
      lines.fail("unknown PLY header keyword " + quote(tokens[0]));
    }
  }
  if (!ended) fail(file, 0, "the PLY header has no 'end_header' line (truncated file?)");
  if (!haveFormat) fail(file, 0, "the PLY header has no 'format' line");
  h.lines = lines.lineNumber();
  h.dataStart = 0;
  for (int i = 0; i < h.lines; ++i) h.dataStart = bytes.find('\n', h.dataStart) + 1;
  if (!h.info.ascii) {
    // OpenMesh finds binary data 12 bytes (14 after "\r\n") past the end of the token before
    // "end_header"; anything else there (trailing blanks, a comment line) shifts every value.
    const size_t endHeaderLine = bytes.rfind("end_header", h.dataStart);
    size_t p = bytes.find_last_not_of(" \t\r\n", endHeaderLine - 1) + 1;
    const size_t lineStart = bytes.rfind('\n', p - 1) + 1;
    if (splitTokens(bytes.substr(lineStart, p - lineStart))[0] == "comment") p = endHeaderLine;
    const size_t openMeshStart = p + (bytes.substr(p, 2) == "\r\n" ? 14 : 12);
    if (openMeshStart != h.dataStart)
      fail(file, h.lines,
           "binary PLY with blanks or a comment just before 'end_header', or blanks "
           "after it: OpenMesh would read the data from the wrong byte");
  }

  checkCounts(bytes, file, h);
  return h;
}

void walkAscii(const Header& h, std::string_view bytes, const std::string& file, PlyInfo& info) {
  LineReader lines(bytes, file, /*joinContinuations=*/false);
  for (int i = 0; i < h.lines; ++i) lines.next();
  std::vector<std::string_view> tokens;
  size_t next = 0;
  std::string where;
  auto take = [&]() -> std::string_view {
    while (next == tokens.size()) {
      if (!lines.next())
        fail(file, lines.lineNumber(), "the file ends inside " + where + " (truncated)");
      tokens = splitTokens(lines.line());
      next = 0;
    }
    return tokens[next++];
  };
  // OpenMesh reads ASCII values with istream >>: every value must be a plain decimal number
  // (integers for integer types), or the reader goes out of step.
  auto integer = [&](PlyType type, const std::string& what) {
    const std::string_view t = take();
    const auto v = parseInt(t);
    const auto [lo, hi] = intRange(type);
    if (!v || *v < lo || *v > hi)
      lines.fail(what + " " + quote(t) + " is not an integer in [" + std::to_string(lo) + ", " +
                 std::to_string(hi) + "]");
    return *v;
  };
  auto number = [&](PlyType type, const std::string& what, bool coordinate) {
    if (!isFloat(type)) return static_cast<double>(integer(type, what));
    const std::string_view t = take();
    const auto v = parseDouble(t);
    if (!v) lines.fail(what + " " + quote(t) + " is not a number");
    if (!std::isfinite(*v))
      lines.fail(what + (coordinate ? " has a NaN or Inf coordinate " : " is NaN or Inf: ") +
                 quote(t));
    return *v;
  };
  for (const PlyElement& e : h.elements)
    for (int64_t item = 0; item < e.count; ++item) {
      where = e.name + " " + std::to_string(item) + " of " + std::to_string(e.count);
      for (const PlyProperty& p : e.properties) {
        const bool coordinate =
            e.name == "vertex" && (p.name == "x" || p.name == "y" || p.name == "z");
        if (!p.list) {
          number(p.type, where, coordinate);
          continue;
        }
        const int64_t n = integer(p.countType, where + " list length");
        const bool indices = e.isFaceIndexList(p);
        if (indices && n < 3)
          lines.fail(where + " has " + std::to_string(n) + " vertices; a face needs at least 3");
        for (int64_t k = 0; k < n; ++k) {
          const double v = number(p.type, where, false);
          if (indices && (v < 0 || v >= static_cast<double>(info.vertices)))
            lines.fail(where + " uses vertex index " + std::to_string(static_cast<int64_t>(v)) +
                       ", out of range [0, " + std::to_string(info.vertices) + ")");
        }
      }
    }
  while (lines.next()) info.trailing += !splitTokens(lines.line()).empty();
}

void walkBinary(const Header& h, std::string_view bytes, const std::string& file, PlyInfo& info) {
  size_t pos = h.dataStart;
  std::string where;
  auto read = [&](PlyType type) -> double {
    const int size = byteSize(type);
    if (bytes.size() - pos < static_cast<size_t>(size))
      fail(file, 0,
           "the file ends at byte " + std::to_string(pos) + " inside " + where + " (truncated)");
    unsigned char b[8];
    std::memcpy(b, bytes.data() + pos, static_cast<size_t>(size));
    pos += static_cast<size_t>(size);
    if (h.bigEndian) std::reverse(b, b + size);
    uint64_t u = 0;
    for (int i = size - 1; i >= 0; --i) u = (u << 8) | b[i];
    switch (type) {
      case PlyType::Int8:
        return static_cast<int8_t>(u);
      case PlyType::UInt8:
        return static_cast<uint8_t>(u);
      case PlyType::Int16:
        return static_cast<int16_t>(u);
      case PlyType::UInt16:
        return static_cast<uint16_t>(u);
      case PlyType::Int32:
        return static_cast<int32_t>(u);
      case PlyType::UInt32:
        return static_cast<uint32_t>(u);
      case PlyType::Float32:
        return std::bit_cast<float>(static_cast<uint32_t>(u));
      default:
        return std::bit_cast<double>(u);
    }
  };
  for (const PlyElement& e : h.elements)
    for (int64_t item = 0; item < e.count; ++item) {
      where = e.name + " " + std::to_string(item) + " of " + std::to_string(e.count);
      for (const PlyProperty& p : e.properties) {
        const size_t at = pos;
        if (!p.list) {
          const double v = read(p.type);
          if (e.name == "vertex" && (p.name == "x" || p.name == "y" || p.name == "z") &&
              !std::isfinite(v))
            fail(file, 0,
                 where + " has a NaN or Inf coordinate (at byte " + std::to_string(at) + ")");
          continue;
        }
        const double n = read(p.countType);
        const bool indices = e.isFaceIndexList(p);
        if (n < 0)
          fail(file, 0, where + " has a negative list length (at byte " + std::to_string(at) + ")");
        if (indices && n < 3)
          fail(file, 0,
               where + " has " + std::to_string(static_cast<int64_t>(n)) +
                   " vertices; a face needs at least 3 (at byte " + std::to_string(at) + ")");
        for (int64_t k = 0; k < static_cast<int64_t>(n); ++k) {
          const double v = read(p.type);
          if (indices && (v < 0 || v >= static_cast<double>(info.vertices)))
            fail(file, 0,
                 where + " uses vertex index " + std::to_string(static_cast<int64_t>(v)) +
                     ", out of range [0, " + std::to_string(info.vertices) + ") (at byte " +
                     std::to_string(at) + ")");
        }
      }
    }
  info.trailing = static_cast<int64_t>(bytes.size() - pos);
}

}  // namespace

PlyInfo checkPly(std::string_view bytes, const std::string& file) {
  const Header h = parseHeader(bytes, file);
  PlyInfo info = h.info;
  if (info.ascii)
    walkAscii(h, bytes, file, info);
  else
    walkBinary(h, bytes, file, info);
  return info;
}

}  // namespace osd_cull::adapters::detail
