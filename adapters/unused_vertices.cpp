#include "adapters/unused_vertices.h"

#include <string>
#include <vector>

namespace osd_cull::adapters {

size_t dropUnusedVertices(CageMesh& mesh) {
  std::vector<int> newIndex(mesh.positions.size(), -1);
  for (int v : mesh.faceVertices) newIndex[static_cast<size_t>(v)] = 0;
  int kept = 0;
  for (size_t v = 0; v < newIndex.size(); ++v)
    if (newIndex[v] == 0) {
      mesh.positions[static_cast<size_t>(kept)] = mesh.positions[v];
      newIndex[v] = kept++;
    }
  const size_t dropped = mesh.positions.size() - static_cast<size_t>(kept);
  if (dropped == 0) return 0;
  mesh.positions.resize(static_cast<size_t>(kept));
  mesh.positions.shrink_to_fit();
  for (int& v : mesh.faceVertices) v = newIndex[static_cast<size_t>(v)];
  for (CreaseEdge& c : mesh.creases) {  // crease edges are face edges: both ends are used
    c.v0 = newIndex[static_cast<size_t>(c.v0)];
    c.v1 = newIndex[static_cast<size_t>(c.v1)];
  }
  std::vector<CornerVertex> corners;
  for (CornerVertex c : mesh.corners)
    if (const int v = newIndex[static_cast<size_t>(c.vertex)]; v >= 0) {
      c.vertex = v;
      corners.push_back(c);
    }
  mesh.corners = std::move(corners);
  mesh.notes.push_back("dropped the " + std::to_string(dropped) +
                       " unused vertices before refinement; the " + std::to_string(kept) +
                       " used ones keep their order");
  return dropped;
}

}  // namespace osd_cull::adapters
