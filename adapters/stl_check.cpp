// checkStl(): binary or ASCII STL, checked the way OpenMesh's reader will read it (see
// format_headers.h).
#include "adapters/format_headers.h"
#include "adapters/text_input.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>

namespace osd_cull::adapters::detail {
namespace {

uint32_t readU32le(std::string_view bytes, size_t at) {
  unsigned char b[4];
  std::memcpy(b, bytes.data() + at, 4);
  return uint32_t{b[3]} << 24 | uint32_t{b[2]} << 16 | uint32_t{b[1]} << 8 | b[0];
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return out;
}

StlInfo checkBinary(std::string_view bytes, const std::string& file, uint32_t triangles) {
  for (uint32_t t = 0; t < triangles; ++t)
    for (size_t k = 3; k < 12; ++k) {  // skip the normal, check the three corners
      const size_t at = 84 + 50 * size_t{t} + 4 * k;
      if (!std::isfinite(std::bit_cast<float>(readU32le(bytes, at))))
        fail(file, 0,
             "binary STL triangle " + std::to_string(t) + " has a NaN or Inf coordinate (at byte " +
                 std::to_string(at) + ")");
    }
  return {true, triangles};
}

// OpenMesh's ASCII reader: a line containing "outer" (or "OUTER") starts a triangle, and the
// next three lines, whatever they are, give its corners as "WORD x y z".
StlInfo checkAscii(std::string_view bytes, const std::string& file) {
  StlInfo info;
  LineReader lines(bytes, file, /*joinContinuations=*/false);
  while (lines.next()) {
    const std::string_view line = lines.line();
    if (line.find("outer") == std::string_view::npos &&
        line.find("OUTER") == std::string_view::npos) {
      const auto tokens = splitTokens(line);
      if (!tokens.empty() && lower(tokens[0]) == "vertex")
        lines.fail("'vertex' outside an 'outer loop'");
      continue;
    }
    for (int corner = 0; corner < 3; ++corner) {
      if (!lines.next())
        fail(file, lines.lineNumber(),
             "the file ends inside a facet after " + std::to_string(corner) +
                 " of 3 vertices (truncated)");
      const auto tokens = splitTokens(lines.line());
      if (tokens.size() != 4 || lower(tokens[0]) != "vertex")
        lines.fail("expected 'vertex x y z' (corner " + std::to_string(corner + 1) +
                   " of 3), found " + quote(lines.line()));
      for (size_t i = 1; i < 4; ++i) {
        const auto v = parseDouble(tokens[i]);
        if (!v) lines.fail("vertex coordinate " + quote(tokens[i]) + " is not a number");
        if (!std::isfinite(*v) || std::abs(*v) > std::numeric_limits<float>::max())
          lines.fail("vertex has a NaN or Inf coordinate (" + quote(tokens[i]) + ")");
      }
    }
    ++info.triangles;
  }
  if (info.triangles == 0) fail(file, 0, "the ASCII STL file has no facets: the mesh is empty");
  return info;
}

}  // namespace

StlInfo checkStl(std::string_view bytes, const std::string& file) {
  if (bytes.size() >= 84) {
    const uint32_t n = readU32le(bytes, 80);
    if (84 + 50 * uint64_t{n} == bytes.size()) {
      if (n == 0) fail(file, 0, "the binary STL file has no triangles: the mesh is empty");
      return checkBinary(bytes, file, n);
    }
  }
  const size_t first = bytes.find_first_not_of(" \t\r\n");
  if (first != std::string_view::npos && lower(bytes.substr(first, 5)) == "solid")
    return checkAscii(bytes, file);
  if (bytes.size() < 84)
    fail(file, 0,
         "neither ASCII STL (no 'solid') nor binary STL (shorter than the 84-byte header)");
  const uint32_t n = readU32le(bytes, 80);
  fail(file, 0,
       "neither ASCII STL (no 'solid') nor binary STL: the header declares " + std::to_string(n) +
           " triangles, " + std::to_string(84 + 50 * uint64_t{n}) + " bytes, but the file has " +
           std::to_string(bytes.size()) + " (truncated file or wrong header)");
}

}  // namespace osd_cull::adapters::detail
