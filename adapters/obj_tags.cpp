#include "adapters/obj_tags.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace osd_cull::adapters::detail {
namespace {

struct TagArgs {
  std::string_view name;
  std::vector<int64_t> ints;
  std::vector<double> floats;
  std::vector<std::string_view> strings;
};

// "t NAME i/f/s ints... floats... strings...", the layout OpenSubdiv's Shape::tag::parseTag
// reads. Unlike that parser (which silently drops a malformed tag), every defect is an error.
TagArgs splitTag(const std::vector<std::string_view>& tokens, const LineReader& at,
                 int& extraArgs) {
  if (tokens.size() < 2) at.fail("tag line 't' without a tag name");
  TagArgs tag;
  tag.name = tokens[1];
  const std::string what = "tag " + quote(tag.name);
  if (tokens.size() < 3)
    at.fail(what + " lacks its argument counts (expected ints/floats/strings, e.g. 2/1/0)");
  int64_t counts[3] = {0, 0, 0};
  {
    std::string_view spec = tokens[2];
    for (int i = 0; i < 3; ++i) {
      const size_t slash = spec.find('/');
      if ((i < 2) == (slash == std::string_view::npos))
        at.fail(what + ": argument counts " + quote(tokens[2]) +
                " are not of the form ints/floats/strings");
      const auto n = parseInt(spec.substr(0, slash));
      if (!n || *n < 0)
        at.fail(what + ": argument counts " + quote(tokens[2]) +
                " are not of the form ints/floats/strings");
      counts[i] = *n;
      spec = slash == std::string_view::npos ? std::string_view() : spec.substr(slash + 1);
    }
  }
  const auto available = static_cast<int64_t>(tokens.size()) - 3;
  if (counts[0] + counts[1] + counts[2] > available)
    at.fail(what + " declares " + std::to_string(counts[0]) + " integer, " +
            std::to_string(counts[1]) + " float and " + std::to_string(counts[2]) +
            " string arguments but the line has " + std::to_string(available));
  if (counts[0] + counts[1] + counts[2] < available) ++extraArgs;
  size_t k = 3;
  for (int64_t i = 0; i < counts[0]; ++i, ++k) {
    const auto v = parseInt(tokens[k]);
    if (!v)
      at.fail(what + ": integer argument " + std::to_string(i + 1) + " is " + quote(tokens[k]) +
              ", not an integer");
    tag.ints.push_back(*v);
  }
  for (int64_t i = 0; i < counts[1]; ++i, ++k) {
    const auto v = parseDouble(tokens[k]);
    if (!v || std::isnan(*v))
      at.fail(what + ": float argument " + std::to_string(i + 1) + " is " + quote(tokens[k]) +
              ", not a number");
    tag.floats.push_back(*v);
  }
  for (int64_t i = 0; i < counts[2]; ++i, ++k) tag.strings.push_back(tokens[k]);
  return tag;
}

// One sharpness per item, or one for all: OpenSubdiv's "(nfloat > 1) ? floatargs[j] :
// floatargs[0]".
float sharpnessFor(const TagArgs& tag, size_t item, size_t items, const LineReader& at) {
  if (tag.floats.size() != 1 && tag.floats.size() != items)
    at.fail("tag " + quote(tag.name) + " needs 1 sharpness or one per " +
            (tag.name == "crease" ? "edge (" : "vertex (") + std::to_string(items) + "), found " +
            std::to_string(tag.floats.size()));
  const double s = tag.floats.size() == 1 ? tag.floats[0] : tag.floats[item];
  if (!std::isfinite(s) || std::abs(s) > std::numeric_limits<float>::max())
    at.fail("tag " + quote(tag.name) + ": sharpness " + std::to_string(s) +
            " is not a finite number");
  return static_cast<float>(s);
}

int64_t singleInt(const TagArgs& tag, const LineReader& at, int64_t maxValue, const char* meaning) {
  if (tag.ints.size() != 1)
    at.fail("tag " + quote(tag.name) + " needs exactly 1 integer argument (" + meaning +
            "), found " + std::to_string(tag.ints.size()));
  if (tag.ints[0] < 0 || tag.ints[0] > maxValue)
    at.fail("tag " + quote(tag.name) + ": value " + std::to_string(tag.ints[0]) +
            " is not one of " + meaning);
  return tag.ints[0];
}

std::string_view singleString(const TagArgs& tag, const LineReader& at, const char* meaning) {
  if (tag.strings.size() != 1)
    at.fail("tag " + quote(tag.name) + " needs exactly 1 string argument (" + meaning +
            "), found " + std::to_string(tag.strings.size()));
  return tag.strings[0];
}

std::string sharpnessText(float s) {
  std::string text = std::to_string(s);
  text.erase(text.find_last_not_of('0') + 1);
  if (text.back() == '.') text.pop_back();
  return text;
}

uint64_t edgeKey(int a, int b) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(std::max(a, b))) << 32) |
         static_cast<uint32_t>(std::min(a, b));
}

}  // namespace

void ObjTags::parse(const std::vector<std::string_view>& tokens, const LineReader& at,
                    Scheme scheme, std::vector<std::string>& notes) {
  const TagArgs tag = splitTag(tokens, at, extraArgs_);
  if (extraArgs_ == 1 && extraArgsLine_ == 0) extraArgsLine_ = at.lineNumber();
  const int line = at.lineNumber();
  noteRepeatedOption(tokens, at, notes);
  auto keep = [&](float s) {
    if (s >= 0.0f) return s;
    if (clampedSharpness_++ == 0) clampedSharpnessLine_ = line;
    return 0.0f;
  };

  if (tag.name == "crease") {
    // RenderMan's and OpenSubdiv 2's reading: the integers are a chain of vertices, each
    // consecutive pair one crease edge. (OpenSubdiv 3's regression harness steps by pairs;
    // both agree on the two-vertex tags all shipped shapes use.)
    if (tag.ints.size() < 2)
      at.fail("tag 'crease' needs at least 2 vertex indices, found " +
              std::to_string(tag.ints.size()));
    const size_t edges = tag.ints.size() - 1;
    for (size_t e = 0; e < edges; ++e)
      creases_.push_back(
          {line, tag.ints[e], tag.ints[e + 1], keep(sharpnessFor(tag, e, edges, at))});
  } else if (tag.name == "corner") {
    if (tag.ints.empty()) at.fail("tag 'corner' needs at least 1 vertex index");
    for (size_t i = 0; i < tag.ints.size(); ++i)
      corners_.push_back({line, tag.ints[i], keep(sharpnessFor(tag, i, tag.ints.size(), at))});
  } else if (tag.name == "hole") {
    if (tag.ints.empty()) at.fail("tag 'hole' needs at least 1 face index");
    for (int64_t f : tag.ints) holes_.push_back({line, f});
  } else if (tag.name == "interpolateboundary") {
    // The mapping of OpenSubdiv's GetSdcOptions (regression/common/far_utils.h).
    static constexpr BoundaryInterpolation kRule[] = {BoundaryInterpolation::None,
                                                      BoundaryInterpolation::EdgeAndCorner,
                                                      BoundaryInterpolation::EdgeOnly};
    boundary_ = kRule[singleInt(tag, at, 2, "0 none, 1 edge-and-corner, 2 edge-only")];
  } else if (tag.name == "facevaryinginterpolateboundary") {
    static constexpr FVarInterpolation kRule[] = {
        FVarInterpolation::None,         FVarInterpolation::CornersOnly,
        FVarInterpolation::CornersPlus1, FVarInterpolation::CornersPlus2,
        FVarInterpolation::Boundaries,   FVarInterpolation::All};
    fvarBoundary_ = kRule[singleInt(
        tag, at, 5, "0 none, 1 corners-only, 2 corners+1, 3 corners+2, 4 boundaries, 5 all")];
  } else if (tag.name == "creasemethod") {
    const std::string_view s = singleString(tag, at, "normal or chaikin");
    if (s == "normal" || s == "uniform")
      creasing_ = CreasingMethod::Uniform;
    else if (s == "chaikin")
      creasing_ = CreasingMethod::Chaikin;
    else
      at.fail("tag 'creasemethod': " + quote(s) + " is not one of normal, uniform, chaikin");
  } else if (tag.name == "smoothtriangles") {
    const std::string_view s = singleString(tag, at, "catmark or smooth");
    TriangleSubdivision t{};
    if (s == "catmark")
      t = TriangleSubdivision::Catmark;
    else if (s == "smooth")
      t = TriangleSubdivision::Smooth;
    else
      at.fail("tag 'smoothtriangles': " + quote(s) + " is not one of catmark, smooth");
    if (scheme == Scheme::CatmullClark)
      triangles_ = t;
    else
      notes.push_back(at.file() + ":" + std::to_string(line) +
                      ": tag 'smoothtriangles' applies to Catmull-Clark meshes only; ignored");
  } else {
    auto [it, inserted] = unknown_.try_emplace(std::string(tag.name), 0, line);
    ++it->second.first;
  }
}

void ObjTags::noteRepeatedOption(const std::vector<std::string_view>& tokens, const LineReader& at,
                                 std::vector<std::string>& notes) {
  const std::string_view name = tokens[1];
  if (name != "interpolateboundary" && name != "facevaryinginterpolateboundary" &&
      name != "creasemethod" && name != "smoothtriangles")
    return;
  std::string value;
  for (size_t i = 3; i < tokens.size(); ++i) value += (i > 3 ? " " : "") + std::string(tokens[i]);
  auto [it, first] = optionTags_.try_emplace(std::string(name), at.lineNumber(), value);
  if (first) return;
  if (it->second.second != value)
    notes.push_back(at.file() + ":" + std::to_string(at.lineNumber()) + ": tag " + quote(name) +
                    " conflicts with line " + std::to_string(it->second.first) + " (" +
                    quote(it->second.second) + " then " + quote(value) +
                    "); the last one is used, as in OpenSubdiv");
  it->second = {at.lineNumber(), value};
}

void ObjTags::apply(CageMesh& mesh, const std::string& file) const {
  const int64_t vertices = mesh.vertexCount();
  auto checkVertex = [&](int64_t v, int line, const char* what) {
    if (v < 0 || v >= vertices)
      fail(file, line,
           std::string(what) + " names vertex " + std::to_string(v) + ", out of range [0, " +
               std::to_string(vertices) + ") (tag indices are 0-based)");
  };

  // The crease edges some face actually has (a scan of the faces, only when there are creases).
  std::unordered_set<uint64_t> wanted, found;
  for (const Crease& c : creases_) {
    checkVertex(c.v0, c.line, "tag 'crease'");
    checkVertex(c.v1, c.line, "tag 'crease'");
    wanted.insert(edgeKey(static_cast<int>(c.v0), static_cast<int>(c.v1)));
  }
  for (size_t f = 0, offset = 0; !wanted.empty() && f < mesh.faceSizes.size();
       offset += static_cast<size_t>(mesh.faceSizes[f++])) {
    const int n = mesh.faceSizes[f];
    for (int k = 0; k < n; ++k) {
      const uint64_t key = edgeKey(mesh.faceVertices[offset + static_cast<size_t>(k)],
                                   mesh.faceVertices[offset + static_cast<size_t>((k + 1) % n)]);
      if (wanted.contains(key)) found.insert(key);
    }
  }
  std::unordered_map<uint64_t, const Crease*> creaseOf;
  for (const Crease& c : creases_) {
    // OpenSubdiv refuses the whole mesh when a crease names a pair of vertices that no face
    // connects; say which pair.
    if (!found.contains(edgeKey(static_cast<int>(c.v0), static_cast<int>(c.v1))))
      fail(file, c.line,
           "tag 'crease': vertices " + std::to_string(c.v0) + " and " + std::to_string(c.v1) +
               " are not joined by an edge of any face");
    mesh.creases.push_back({static_cast<int>(c.v0), static_cast<int>(c.v1), c.sharpness});
    // OpenSubdiv keeps the last sharpness given to an edge; a different earlier one is
    // probably a mistake worth a note.
    const Crease*& before = creaseOf[edgeKey(static_cast<int>(c.v0), static_cast<int>(c.v1))];
    if (before && before->sharpness != c.sharpness)
      mesh.notes.push_back(file + ":" + std::to_string(c.line) + ": edge (" + std::to_string(c.v0) +
                           ", " + std::to_string(c.v1) + ") is creased again with sharpness " +
                           sharpnessText(c.sharpness) + " (line " + std::to_string(before->line) +
                           " gave " + sharpnessText(before->sharpness) + "); the last one is used");
    before = &c;
  }
  std::unordered_map<int64_t, const Corner*> cornerOf;
  for (const Corner& c : corners_) {
    checkVertex(c.vertex, c.line, "tag 'corner'");
    const Corner*& before = cornerOf[c.vertex];
    if (before && before->sharpness != c.sharpness)
      mesh.notes.push_back(file + ":" + std::to_string(c.line) + ": vertex " +
                           std::to_string(c.vertex) + " is given corner sharpness " +
                           sharpnessText(c.sharpness) + " again (line " +
                           std::to_string(before->line) + " gave " +
                           sharpnessText(before->sharpness) + "); the last one is used");
    before = &c;
    mesh.corners.push_back({static_cast<int>(c.vertex), c.sharpness});
  }
  for (const Hole& h : holes_) {
    if (h.face < 0 || h.face >= mesh.faceCount())
      fail(file, h.line,
           "tag 'hole' names face " + std::to_string(h.face) + ", out of range [0, " +
               std::to_string(mesh.faceCount()) + ") (tag indices are 0-based)");
    mesh.holes.push_back(static_cast<int>(h.face));
  }
  if (boundary_) mesh.boundary = *boundary_;
  if (fvarBoundary_) mesh.fvarBoundary = *fvarBoundary_;
  if (creasing_) mesh.creasing = *creasing_;
  if (triangles_) mesh.triangles = *triangles_;
}

void ObjTags::finishNotes(std::vector<std::string>& notes) const {
  for (const auto& [name, use] : unknown_)
    notes.push_back("ignored " + std::to_string(use.first) + " tag line(s) with unknown tag " +
                    quote(name) + " (first at line " + std::to_string(use.second) + ")");
  if (clampedSharpness_)
    notes.push_back(std::to_string(clampedSharpness_) +
                    " negative sharpness value(s) clamped to 0 as OpenSubdiv "
                    "does (first at line " +
                    std::to_string(clampedSharpnessLine_) + ")");
  if (extraArgs_)
    notes.push_back(std::to_string(extraArgs_) +
                    " tag line(s) have more arguments than declared; the extra ones "
                    "were ignored (first at line " +
                    std::to_string(extraArgsLine_) + ")");
}

}  // namespace osd_cull::adapters::detail
