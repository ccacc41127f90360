#include "adapters/off_reader.h"

#include "adapters/text_input.h"

#include <climits>
#include <cmath>
#include <vector>

namespace osd_cull::adapters::detail {
namespace {

std::vector<std::string_view> tokensBeforeComment(std::string_view line) {
  return splitTokens(line.substr(0, line.find('#')));
}

// Advances to the next line with content; false at the end of the text.
bool nextContentLine(LineReader& lines, std::vector<std::string_view>& tokens) {
  while (lines.next()) {
    tokens = tokensBeforeComment(lines.line());
    if (!tokens.empty()) return true;
  }
  return false;
}

// "OFF" with any of the optional prefixes ST (texture), C (colour), N (normal); 4 and n
// (higher-dimensional) are refused.
bool isOffKeyword(std::string_view k, const LineReader& at) {
  if (!k.ends_with("OFF")) return false;
  std::string_view prefix = k.substr(0, k.size() - 3);
  if (prefix.find('4') != std::string_view::npos || prefix.find('n') != std::string_view::npos)
    at.fail("higher-dimensional OFF (" + quote(k) + ") is not supported; expected 3D OFF");
  if (prefix.starts_with("ST")) prefix.remove_prefix(2);
  if (prefix.starts_with("C")) prefix.remove_prefix(1);
  if (prefix.starts_with("N")) prefix.remove_prefix(1);
  return prefix.empty();
}

int64_t count(std::string_view token, const char* what, const LineReader& at) {
  const auto n = parseInt(token);
  if (!n || *n < 0) at.fail(std::string("the ") + what + " count " + quote(token) + " is not a non-negative integer");
  if (*n > INT_MAX) at.fail(std::string("the ") + what + " count " + std::to_string(*n) + " is too large");
  return *n;
}

}  // namespace

bool isBinaryOff(std::string_view text) {
  const size_t end = text.find('\n');
  const auto tokens = tokensBeforeComment(text.substr(0, end));
  return tokens.size() >= 2 && tokens[0].ends_with("OFF") && tokens[1] == "BINARY";
}

CageMesh readOff(std::string_view text, const std::string& file, Scheme scheme) {
  LineReader lines(text, file, /*joinContinuations=*/false);
  std::vector<std::string_view> tokens;
  if (!nextContentLine(lines, tokens)) fail(file, 0, "the file is empty; expected an OFF header");
  size_t next = 0;  // first unread token of the current line
  if (isOffKeyword(tokens[0], lines)) {
    next = 1;
  } else if (!parseInt(tokens[0])) {
    lines.fail("expected the OFF header keyword, found " + quote(tokens[0]));
  }  // else: the keyword is optional; the counts come first
  if (next == tokens.size()) {
    if (!nextContentLine(lines, tokens)) fail(file, 0, "the file ends before the vertex and face counts");
    next = 0;
  }
  if (tokens.size() - next < 2) lines.fail("expected the counts 'vertices faces edges'");
  const int64_t nv = count(tokens[next], "vertex", lines);
  const int64_t nf = count(tokens[next + 1], "face", lines);
  if (nv == 0 || nf == 0) lines.fail("the header declares " + std::to_string(nv) + " vertices and " +
                                     std::to_string(nf) + " faces: the mesh is empty");
  // Every record takes a line: counts beyond the lines left are a wrong header or a
  // truncated file, and must not turn into a huge allocation.
  const auto left = static_cast<int64_t>(lines.remainingLines());
  if (nv + nf > left)
    lines.fail("the header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
               " faces, but only " + std::to_string(left) + " lines follow (truncated file or wrong header)");

  CageMesh mesh;
  mesh.source = file;
  mesh.scheme = scheme;
  mesh.positions.reserve(static_cast<size_t>(nv));
  for (int64_t v = 0; v < nv; ++v) {
    if (!nextContentLine(lines, tokens))
      fail(file, lines.lineNumber(), "the file ends after " + std::to_string(v) + " of " + std::to_string(nv) +
                                         " vertices (truncated)");
    if (tokens.size() < 3) lines.fail("vertex needs 3 coordinates, found " + std::to_string(tokens.size()));
    double c[3];
    for (size_t i = 0; i < 3; ++i) {
      const auto value = parseDouble(tokens[i]);
      if (!value) lines.fail("vertex coordinate " + quote(tokens[i]) + " is not a number");
      if (!std::isfinite(*value))
        lines.fail("vertex " + std::to_string(v) + " has a NaN or Inf coordinate (" + quote(tokens[i]) + ")");
      c[i] = *value;
    }
    mesh.positions.emplace_back(c[0], c[1], c[2]);
  }
  mesh.faceSizes.reserve(static_cast<size_t>(nf));
  for (int64_t f = 0; f < nf; ++f) {
    if (!nextContentLine(lines, tokens))
      fail(file, lines.lineNumber(), "the file ends after " + std::to_string(f) + " of " + std::to_string(nf) +
                                         " faces (truncated)");
    const auto n = parseInt(tokens[0]);
    if (!n) lines.fail("face vertex count " + quote(tokens[0]) + " is not an integer");
    if (*n < 3) lines.fail("face with " + std::to_string(*n) + " vertices; a face needs at least 3");
    if (*n > static_cast<int64_t>(tokens.size()) - 1)
      lines.fail("face declares " + std::to_string(*n) + " vertices but the line lists " +
                 std::to_string(tokens.size() - 1));
    if (scheme == Scheme::Loop && *n != 3)
      lines.fail("face with " + std::to_string(*n) + " vertices, but the Loop scheme needs triangles");
    for (int64_t k = 1; k <= *n; ++k) {
      const auto index = parseInt(tokens[static_cast<size_t>(k)]);
      if (!index) lines.fail("vertex index " + quote(tokens[static_cast<size_t>(k)]) + " is not an integer");
      if (*index < 0 || *index >= nv)
        lines.fail("vertex index " + std::to_string(*index) + " is out of range [0, " + std::to_string(nv) + ")");
      mesh.faceVertices.push_back(static_cast<int>(*index));
    }
    mesh.faceSizes.push_back(static_cast<int>(*n));
  }
  if (nextContentLine(lines, tokens))
    mesh.notes.push_back(file + ":" + std::to_string(lines.lineNumber()) +
                         ": content after the last face was ignored");
  return mesh;
}

}  // namespace osd_cull::adapters::detail
