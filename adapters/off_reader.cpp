#include "adapters/off_reader.h"

#include "adapters/text_input.h"

#include <bit>
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
  if (!n || *n < 0)
    at.fail(std::string("the ") + what + " count " + quote(token) +
            " is not a non-negative integer");
  if (*n > INT_MAX)
    at.fail(std::string("the ") + what + " count " + std::to_string(*n) + " is too large");
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
    if (!nextContentLine(lines, tokens))
      fail(file, 0, "the file ends before the vertex and face counts");
    next = 0;
  }
  if (tokens.size() - next < 2) lines.fail("expected the counts 'vertices faces edges'");
  const int64_t nv = count(tokens[next], "vertex", lines);
  const int64_t nf = count(tokens[next + 1], "face", lines);
  if (nv == 0 || nf == 0)
    lines.fail("the header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
               " faces: the mesh is empty");
  // Every record takes a line: counts beyond the lines left are a wrong header or a
  // truncated file, and must not turn into a huge allocation.
  const auto left = static_cast<int64_t>(lines.remainingLines());
  if (nv + nf > left)
    lines.fail("the header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
               " faces, but only " + std::to_string(left) +
               " lines follow (truncated file or wrong header)");

  CageMesh mesh;
  mesh.source = file;
  mesh.scheme = scheme;
  mesh.positions.reserve(static_cast<size_t>(nv));
  for (int64_t v = 0; v < nv; ++v) {
    if (!nextContentLine(lines, tokens))
      fail(file, lines.lineNumber(),
           "the file ends after " + std::to_string(v) + " of " + std::to_string(nv) +
               " vertices (truncated)");
    if (tokens.size() < 3)
      lines.fail("vertex needs 3 coordinates, found " + std::to_string(tokens.size()));
    double c[3];
    for (size_t i = 0; i < 3; ++i) {
      const auto value = parseDouble(tokens[i]);
      if (!value) lines.fail("vertex coordinate " + quote(tokens[i]) + " is not a number");
      if (!std::isfinite(*value))
        lines.fail("vertex " + std::to_string(v) + " has a NaN or Inf coordinate (" +
                   quote(tokens[i]) + ")");
      c[i] = *value;
    }
    mesh.positions.emplace_back(c[0], c[1], c[2]);
  }
  mesh.faceSizes.reserve(static_cast<size_t>(nf));
  for (int64_t f = 0; f < nf; ++f) {
    if (!nextContentLine(lines, tokens))
      fail(file, lines.lineNumber(),
           "the file ends after " + std::to_string(f) + " of " + std::to_string(nf) +
               " faces (truncated)");
    const auto n = parseInt(tokens[0]);
    if (!n) lines.fail("face vertex count " + quote(tokens[0]) + " is not an integer");
    if (*n < 3)
      lines.fail("face with " + std::to_string(*n) + " vertices; a face needs at least 3");
    if (*n > static_cast<int64_t>(tokens.size()) - 1)
      lines.fail("face declares " + std::to_string(*n) + " vertices but the line lists " +
                 std::to_string(tokens.size() - 1));
    if (scheme == Scheme::Loop && *n != 3)
      lines.fail("face with " + std::to_string(*n) +
                 " vertices, but the Loop scheme needs triangles");
    for (int64_t k = 1; k <= *n; ++k) {
      const auto index = parseInt(tokens[static_cast<size_t>(k)]);
      if (!index)
        lines.fail("vertex index " + quote(tokens[static_cast<size_t>(k)]) + " is not an integer");
      if (*index < 0 || *index >= nv)
        lines.fail("vertex index " + std::to_string(*index) + " is out of range [0, " +
                   std::to_string(nv) + ")");
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

namespace osd_cull::adapters::detail {
namespace {

// Reads 32-bit words of a binary OFF body in one byte order, failing at the end of data.
class WordReader {
 public:
  WordReader(std::string_view bytes, size_t start, bool bigEndian, const std::string& file)
      : bytes_(bytes), pos_(start), bigEndian_(bigEndian), file_(file) {}

  uint32_t word(const std::string& what) {
    if (bytes_.size() - pos_ < 4)
      fail(file_, 0,
           "the file ends at byte " + std::to_string(pos_) + " while reading " + what +
               " (truncated)");
    const auto* b = reinterpret_cast<const unsigned char*>(bytes_.data() + pos_);
    pos_ += 4;
    return bigEndian_ ? (uint32_t{b[0]} << 24 | uint32_t{b[1]} << 16 | uint32_t{b[2]} << 8 | b[3])
                      : (uint32_t{b[3]} << 24 | uint32_t{b[2]} << 16 | uint32_t{b[1]} << 8 | b[0]);
  }
  int64_t integer(const std::string& what) { return static_cast<int32_t>(word(what)); }
  float real(const std::string& what) { return std::bit_cast<float>(word(what)); }
  size_t position() const { return pos_; }
  size_t remainingWords() const { return (bytes_.size() - pos_) / 4; }

 private:
  std::string_view bytes_;
  size_t pos_;
  bool bigEndian_;
  const std::string& file_;
};

}  // namespace

CageMesh readBinaryOff(std::string_view bytes, const std::string& file, Scheme scheme) {
  const size_t eol = bytes.find('\n');
  if (eol == std::string_view::npos) fail(file, 0, "binary OFF file ends inside its header line");
  // A vertex is 3 words, a face at least 5 (count, three indices, colour count). Counts that
  // cannot fit the rest of the file are the wrong byte order, a bad header or a truncation.
  auto fits = [&](bool bigEndian) {
    WordReader r(bytes, eol + 1, bigEndian, file);
    if (r.remainingWords() < 3) return false;
    const int64_t nv = r.integer("the counts"), nf = r.integer("the counts");
    return nv > 0 && nf > 0 && 3 + 3 * nv + 5 * nf <= static_cast<int64_t>(r.remainingWords()) + 3;
  };
  const bool bigEndian = fits(true);
  if (!bigEndian && !fits(false)) {
    WordReader r(bytes, eol + 1, true, file);
    const int64_t nv = r.integer("the counts"), nf = r.integer("the counts");
    fail(file, 0,
         "the binary OFF header declares " + std::to_string(nv) + " vertices and " +
             std::to_string(nf) + " faces, which do not fit the " +
             std::to_string(bytes.size() - eol - 1) +
             " bytes that follow in either byte order (empty, truncated or wrong header)");
  }
  WordReader in(bytes, eol + 1, bigEndian, file);
  const int64_t nv = in.integer("the counts"), nf = in.integer("the counts");
  in.integer("the counts");  // edges: unused

  CageMesh mesh;
  mesh.source = file;
  mesh.scheme = scheme;
  mesh.positions.reserve(static_cast<size_t>(nv));
  for (int64_t v = 0; v < nv; ++v) {
    const std::string what = "vertex " + std::to_string(v);
    const size_t at = in.position();
    const double x = in.real(what), y = in.real(what), z = in.real(what);
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
      fail(file, 0, what + " has a NaN or Inf coordinate (at byte " + std::to_string(at) + ")");
    mesh.positions.emplace_back(x, y, z);
  }
  for (int64_t f = 0; f < nf; ++f) {
    const std::string what = "face " + std::to_string(f);
    const size_t at = in.position();
    const int64_t n = in.integer(what);
    if (n < 3)
      fail(file, 0,
           what + " has " + std::to_string(n) + " vertices; a face needs at least 3 (at byte " +
               std::to_string(at) + ")");
    if (n > static_cast<int64_t>(in.remainingWords()))
      fail(file, 0,
           what + " declares " + std::to_string(n) +
               " vertices, more than the file holds (at byte " + std::to_string(at) + ")");
    if (scheme == Scheme::Loop && n != 3)
      fail(file, 0,
           what + " has " + std::to_string(n) + " vertices, but the Loop scheme needs triangles");
    for (int64_t k = 0; k < n; ++k) {
      const int64_t index = in.integer(what);
      if (index < 0 || index >= nv)
        fail(file, 0,
             what + " uses vertex index " + std::to_string(index) + ", out of range [0, " +
                 std::to_string(nv) + ")");
      mesh.faceVertices.push_back(static_cast<int>(index));
    }
    mesh.faceSizes.push_back(static_cast<int>(n));
    const int64_t colours = in.integer(what + "'s colour count");
    if (colours < 0 || colours > 4)
      fail(file, 0,
           what + " has a colour count of " + std::to_string(colours) + "; expected 0 to 4");
    for (int64_t c = 0; c < colours; ++c) in.real(what + "'s colour");
  }
  if (!bigEndian)
    mesh.notes.push_back(
        "binary OFF in little-endian byte order (the specification says big-endian)");
  return mesh;
}

}  // namespace osd_cull::adapters::detail
