#include "adapters/obj_reader.h"

#include "adapters/obj_tags.h"
#include "adapters/text_input.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace osd_cull::adapters::detail {
namespace {

// Keywords of the OBJ geometry subset that carry nothing a subdivision cage needs; they are
// accepted without a note.
bool isQuietKeyword(std::string_view k) {
  return k == "g" || k == "s" || k == "o" || k == "usemtl" || k == "mtllib";
}

class ObjParser {
 public:
  ObjParser(std::string_view text, const std::filesystem::path& path, Scheme scheme)
      : path_(path), lines_(text, path.string(), /*joinContinuations=*/true) {
    mesh_.source = path.string();
    mesh_.scheme = scheme;
  }

  CageMesh run(bool leftHanded) {
    while (lines_.next()) {
      std::vector<std::string_view> tokens = splitTokens(lines_.line());
      // A token starting with '#' begins a comment (whole-line comments include "#t").
      tokens.erase(
          std::find_if(tokens.begin(), tokens.end(), [](auto t) { return t.front() == '#'; }),
          tokens.end());
      if (tokens.empty()) continue;
      const std::string_view key = tokens[0];
      if (key == "v")
        vertex(tokens);
      else if (key == "vt")
        textureCoordinate(tokens);
      else if (key == "vn")
        numbers(tokens, 3, "normal");
      else if (key == "f" || key == "fo")
        face(tokens);
      else if (key == "t")
        tags_.parse(tokens, lines_, mesh_.scheme, mesh_.notes);
      else if (key == "mtllib")
        materialLibraries(tokens);
      else if (!isQuietKeyword(key))
        ignore(key);
    }
    finish(leftHanded);
    return std::move(mesh_);
  }

 private:
  void vertex(const std::vector<std::string_view>& tokens) {
    if (tokens.size() < 4)
      lines_.fail("vertex needs 3 coordinates, found " + std::to_string(tokens.size() - 1));
    double c[3];
    for (int i = 0; i < 3; ++i) {
      const auto value = parseDouble(tokens[static_cast<size_t>(i) + 1]);
      if (!value)
        lines_.fail("vertex coordinate " + quote(tokens[static_cast<size_t>(i) + 1]) +
                    " is not a number");
      if (!std::isfinite(*value))
        lines_.fail("vertex " + std::to_string(mesh_.positions.size() + 1) +
                    " has a NaN or Inf coordinate (" + quote(tokens[static_cast<size_t>(i) + 1]) +
                    ")");
      c[i] = *value;
    }
    // Further numbers (w, or the r g b some exporters append) do not affect the cage.
    mesh_.positions.emplace_back(c[0], c[1], c[2]);
  }

  void numbers(const std::vector<std::string_view>& tokens, size_t needed, const char* what) {
    if (tokens.size() < needed + 1)
      lines_.fail(std::string(what) + " needs " + std::to_string(needed) + " number(s), found " +
                  std::to_string(tokens.size() - 1));
    for (size_t i = 1; i < tokens.size(); ++i)
      if (!parseDouble(tokens[i]))
        lines_.fail(std::string(what) + " component " + quote(tokens[i]) + " is not a number");
  }

  // "vt u [v [w]]": u and v are the face-varying channel (v = 0 when absent).
  void textureCoordinate(const std::vector<std::string_view>& tokens) {
    numbers(tokens, 1, "texture coordinate");
    const double u = *parseDouble(tokens[1]);
    const double v = tokens.size() > 2 ? *parseDouble(tokens[2]) : 0.0;
    if (!std::isfinite(u) || !std::isfinite(v))
      lines_.fail("texture coordinate " + std::to_string(mesh_.uvs.size() + 1) +
                  " has a NaN or Inf component");
    mesh_.uvs.emplace_back(u, v);
  }

  // The texture-coordinate index of a face corner (0-based; negative indices count back
  // from the last `vt` so far), -1 when the corner has none.
  int uvReference(std::string_view vt, std::string_view token) {
    if (vt.empty()) return -1;
    const int64_t index = *parseInt(vt);
    const auto defined = static_cast<int64_t>(mesh_.uvs.size());
    if (index == 0 || index > INT_MAX || -index > defined)
      lines_.fail("texture-coordinate index in face corner " + quote(token) +
                  " is out of range (" + std::to_string(defined) + " defined so far)");
    return static_cast<int>(index < 0 ? defined + index : index - 1);
  }

  // One corner of a face: "v", "v/vt", "v//vn" or "v/vt/vn"; negative indices count back
  // from the last vertex defined so far. `uv` gets the corner's texture coordinate (-1: none).
  int vertexReference(std::string_view token, int& uv) {
    uv = -1;
    const size_t slash = token.find('/');
    const std::string_view v = token.substr(0, slash);
    if (slash != std::string_view::npos) {
      const std::string_view rest = token.substr(slash + 1);
      const size_t slash2 = rest.find('/');
      const std::string_view vt = rest.substr(0, slash2);
      const std::string_view vn =
          slash2 == std::string_view::npos ? std::string_view() : rest.substr(slash2 + 1);
      if ((!vt.empty() && !parseInt(vt)) || (!vn.empty() && !parseInt(vn)) ||
          (slash2 != std::string_view::npos && vn.empty()))
        lines_.fail("face corner " + quote(token) +
                    " is not of the form v, v/vt, v//vn or v/vt/vn");
      uv = uvReference(vt, token);
    }
    const auto index = parseInt(v);
    if (!index) lines_.fail("face corner " + quote(token) + " does not start with a vertex index");
    if (*index == 0)
      lines_.fail("vertex index 0 in face corner " + quote(token) + " (OBJ indices start at 1)");
    const auto defined = static_cast<int64_t>(mesh_.positions.size());
    if (*index < 0) {
      if (-*index > defined)
        lines_.fail("relative vertex index " + std::to_string(*index) +
                    " reaches before the first vertex (" + std::to_string(defined) +
                    " defined so far)");
      return static_cast<int>(defined + *index);
    }
    if (*index > INT_MAX)
      lines_.fail("vertex index " + std::to_string(*index) + " is out of range");
    return static_cast<int>(*index - 1);  // checked against the final count in finish()
  }

  void face(const std::vector<std::string_view>& tokens) {
    const size_t n = tokens.size() - 1;
    if (n < 3) lines_.fail("face with " + std::to_string(n) + " vertices; a face needs at least 3");
    if (mesh_.scheme == Scheme::Loop && n != 3)
      lines_.fail("face with " + std::to_string(n) +
                  " vertices, but the Loop scheme needs triangles");
    for (size_t i = 1; i < tokens.size(); ++i) {
      int uv = -1;
      mesh_.faceVertices.push_back(vertexReference(tokens[i], uv));
      mesh_.faceUVs.push_back(uv);
      cornersWithoutUV_ += uv < 0 ? 1 : 0;
    }
    mesh_.faceSizes.push_back(static_cast<int>(n));
    faceLines_.push_back(lines_.lineNumber());
  }

  void materialLibraries(const std::vector<std::string_view>& tokens) {
    // Materials do not affect the cage; a missing library is worth a note, not an error.
    for (size_t i = 1; i < tokens.size(); ++i) {
      std::error_code ec;
      if (!std::filesystem::exists(path_.parent_path() / std::string(tokens[i]), ec))
        mesh_.notes.push_back(lines_.file() + ":" + std::to_string(lines_.lineNumber()) +
                              ": material library " + quote(tokens[i]) +
                              " not found (materials are not used)");
    }
  }

  void ignore(std::string_view key) {
    auto [it, inserted] = ignored_.try_emplace(std::string(key), 0, lines_.lineNumber());
    ++it->second.first;
  }

  void finish(bool leftHanded) {
    const std::string& file = lines_.file();
    for (const auto& [key, use] : ignored_)
      mesh_.notes.push_back("ignored " + std::to_string(use.first) +
                            " line(s) with unknown keyword " + quote(key) + " (first at line " +
                            std::to_string(use.second) + ")");
    tags_.finishNotes(mesh_.notes);
    if (mesh_.positions.empty()) fail(file, 0, "no vertices ('v' lines): the mesh is empty");
    if (mesh_.faceSizes.empty()) fail(file, 0, "no faces ('f' lines): the mesh is empty");

    size_t offset = 0;
    for (size_t f = 0; f < mesh_.faceSizes.size(); ++f) {
      const auto n = static_cast<size_t>(mesh_.faceSizes[f]);
      for (size_t k = 0; k < n; ++k) {
        const int v = mesh_.faceVertices[offset + k];
        if (v >= mesh_.vertexCount())
          fail(file, faceLines_[f],
               "face uses vertex " + std::to_string(v + 1) + ", but the file defines only " +
                   std::to_string(mesh_.vertexCount()) + " vertices");
      }
      // OpenSubdiv's Shape with isLeftHanded: keep the first vertex, reverse the rest.
      if (leftHanded) {
        const auto first = static_cast<std::ptrdiff_t>(offset + 1);
        const auto last = static_cast<std::ptrdiff_t>(offset + n);
        std::reverse(mesh_.faceVertices.begin() + first, mesh_.faceVertices.begin() + last);
        std::reverse(mesh_.faceUVs.begin() + first, mesh_.faceUVs.begin() + last);
      }
      offset += n;
    }
    // Texture coordinates form a face-varying channel only when every corner has one.
    if (cornersWithoutUV_ > 0) {
      if (cornersWithoutUV_ < mesh_.faceUVs.size())
        mesh_.notes.push_back(std::to_string(cornersWithoutUV_) + " of " +
                              std::to_string(mesh_.faceUVs.size()) +
                              " face corners have no texture coordinate: the mesh is read "
                              "without texture coordinates");
      mesh_.faceUVs.clear();
      mesh_.uvs.clear();
    }
    tags_.apply(mesh_, file);
  }

  std::filesystem::path path_;
  LineReader lines_;
  CageMesh mesh_;
  ObjTags tags_;
  std::vector<int> faceLines_;
  size_t cornersWithoutUV_ = 0;
  std::map<std::string, std::pair<int, int>> ignored_;  // keyword → (count, first line)
};

}  // namespace

CageMesh readObj(std::string_view text, const std::filesystem::path& path, Scheme scheme,
                 bool leftHanded) {
  return ObjParser(text, path, scheme).run(leftHanded);
}

}  // namespace osd_cull::adapters::detail
