#include "osd_cull/bound/back_patch_validity.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace osd_cull::bound {

BackPatchValidity backPatchValidity(const TopologySummary& t, std::optional<double> signedVol) {
  auto disabled = [](std::string why) { return BackPatchValidity{false, std::move(why)}; };
  if (t.faces == 0) return disabled("the mesh has no faces");
  if (t.nonManifoldEdges > 0)
    return disabled(std::to_string(t.nonManifoldEdges) +
                    " non-manifold edges (more than two faces, or faces that disagree on "
                    "orientation)");
  if (t.nonManifoldVertices > 0)
    return disabled(std::to_string(t.nonManifoldVertices) +
                    " non-manifold vertices (orientation around them is not verified)");
  if (t.boundaryEdges > 0)
    return disabled("the surface is open: " + std::to_string(t.boundaryEdges) +
                    " boundary edges (the inside can be seen through them)");
  if (t.holes > 0)
    return disabled("the surface is open: " + std::to_string(t.holes) + " faces are holes");
  if (!signedVol)
    return {true, "closed and manifold; outward orientation assumed (no signed volume given)"};
  if (!std::isfinite(*signedVol)) return disabled("the signed volume is not finite");
  if (*signedVol < 0.0)
    return disabled(
        "the faces are oriented inward (negative signed volume); reverse the "
        "face vertex order to enable back-patch culling");
  if (*signedVol == 0.0) return disabled("the surface encloses no volume");
  return {true, "closed, manifold and oriented outward"};
}

double signedVolume(const CageMesh& mesh) {
  std::vector<bool> hole(mesh.faceSizes.size(), false);
  for (int h : mesh.holes)
    if (h >= 0 && static_cast<size_t>(h) < hole.size()) hole[h] = true;
  // Σ over fan triangles (p0, pi, pi+1) of det(p0, pi, pi+1) / 6, relative to a point of
  // the mesh so that a mesh far from the origin loses no precision.
  const glm::dvec3 origin = mesh.positions.empty() ? glm::dvec3(0.0) : mesh.positions.front();
  double volume = 0.0;
  size_t first = 0;
  for (size_t f = 0; f < mesh.faceSizes.size(); ++f) {
    const int n = mesh.faceSizes[f];
    if (!hole[f]) {
      const glm::dvec3 p0 = mesh.positions[mesh.faceVertices[first]] - origin;
      for (int i = 1; i + 1 < n; ++i) {
        const glm::dvec3 p1 = mesh.positions[mesh.faceVertices[first + i]] - origin;
        const glm::dvec3 p2 = mesh.positions[mesh.faceVertices[first + i + 1]] - origin;
        volume += glm::dot(p0, glm::cross(p1, p2)) / 6.0;
      }
    }
    first += static_cast<size_t>(n);
  }
  return volume;
}

CullablePatches cullablePatches(const CageMesh& cage, const PatchOptions& options) {
  CullablePatches out;
  out.extraction = extractPatches(cage, options);
  out.backPatch = backPatchValidity(out.extraction.topology, signedVolume(cage));
  return out;
}

}  // namespace osd_cull::bound
