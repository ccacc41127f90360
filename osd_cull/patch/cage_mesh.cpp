#include "osd_cull/patch/cage_mesh.h"

#include "osd_cull/error.h"

#include <cmath>
#include <string>

namespace osd_cull {

std::string_view toString(Scheme scheme) {
  switch (scheme) {
    case Scheme::CatmullClark:
      return "catmark";
    case Scheme::Loop:
      return "loop";
    case Scheme::Bilinear:
      return "bilinear";
  }
  return "unknown";
}

std::optional<Scheme> schemeFromString(std::string_view text) {
  if (text == "catmark" || text == "catmull-clark" || text == "catmullclark")
    return Scheme::CatmullClark;
  if (text == "loop") return Scheme::Loop;
  if (text == "bilinear") return Scheme::Bilinear;
  return std::nullopt;
}

std::optional<Scheme> schemeFromFileName(std::string_view path) {
  const auto slash = path.find_last_of("/\\");
  const std::string_view name = slash == std::string_view::npos ? path : path.substr(slash + 1);
  if (name.starts_with("catmark_")) return Scheme::CatmullClark;
  if (name.starts_with("loop_")) return Scheme::Loop;
  if (name.starts_with("bilinear_")) return Scheme::Bilinear;
  return std::nullopt;
}

void validate(const CageMesh& mesh) {
  const std::string where = mesh.source.empty() ? std::string("mesh") : mesh.source;
  if (mesh.positions.empty()) throw Error(where + ": the mesh has no vertices");
  if (mesh.faceSizes.empty()) throw Error(where + ": the mesh has no faces");
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::dvec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error(where + ": vertex " + std::to_string(i) + " has a NaN or Inf coordinate");
  }
  size_t offset = 0;
  for (size_t f = 0; f < mesh.faceSizes.size(); ++f) {
    const int n = mesh.faceSizes[f];
    if (n < 3)
      throw Error(where + ": face " + std::to_string(f) + " has " + std::to_string(n) +
                  " vertices; a face needs at least 3");
    if (offset + static_cast<size_t>(n) > mesh.faceVertices.size())
      throw Error(where + ": face " + std::to_string(f) + " runs past the face-vertex list");
    for (int k = 0; k < n; ++k) {
      const int v = mesh.faceVertices[offset + static_cast<size_t>(k)];
      if (v < 0 || v >= mesh.vertexCount())
        throw Error(where + ": face " + std::to_string(f) + " uses vertex index " +
                    std::to_string(v) + ", out of range [0, " + std::to_string(mesh.vertexCount()) +
                    ")");
    }
    offset += static_cast<size_t>(n);
  }
  if (offset != mesh.faceVertices.size())
    throw Error(where + ": face-vertex list has " + std::to_string(mesh.faceVertices.size()) +
                " entries, faces use " + std::to_string(offset));
  auto checkSharpness = [&](float s, const std::string& what) {
    if (!std::isfinite(s) || s < 0.0f)
      throw Error(where + ": " + what + " has sharpness " + std::to_string(s) +
                  "; expected a finite number >= 0");
  };
  for (const CreaseEdge& c : mesh.creases) {
    if (c.v0 < 0 || c.v0 >= mesh.vertexCount() || c.v1 < 0 || c.v1 >= mesh.vertexCount())
      throw Error(where + ": crease (" + std::to_string(c.v0) + ", " + std::to_string(c.v1) +
                  ") names a vertex out of range");
    checkSharpness(c.sharpness,
                   "crease (" + std::to_string(c.v0) + ", " + std::to_string(c.v1) + ")");
  }
  for (const CornerVertex& c : mesh.corners) {
    if (c.vertex < 0 || c.vertex >= mesh.vertexCount())
      throw Error(where + ": corner vertex " + std::to_string(c.vertex) + " is out of range");
    checkSharpness(c.sharpness, "corner " + std::to_string(c.vertex));
  }
  for (int h : mesh.holes)
    if (h < 0 || h >= mesh.faceCount())
      throw Error(where + ": hole face " + std::to_string(h) + " is out of range");
  if (mesh.faceUVs.empty()) return;
  if (mesh.faceUVs.size() != mesh.faceVertices.size())
    throw Error(where + ": " + std::to_string(mesh.faceUVs.size()) +
                " texture-coordinate indices for " + std::to_string(mesh.faceVertices.size()) +
                " face corners");
  for (size_t i = 0; i < mesh.uvs.size(); ++i)
    if (!std::isfinite(mesh.uvs[i].x) || !std::isfinite(mesh.uvs[i].y))
      throw Error(where + ": texture coordinate " + std::to_string(i) + " is NaN or Inf");
  for (int t : mesh.faceUVs)
    if (t < 0 || static_cast<size_t>(t) >= mesh.uvs.size())
      throw Error(where + ": texture-coordinate index " + std::to_string(t) + " is out of range (" +
                  std::to_string(mesh.uvs.size()) + " defined)");
}

}  // namespace osd_cull
