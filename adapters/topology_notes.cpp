#include "adapters/topology_notes.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace osd_cull::adapters {
namespace {

// One traversal of an edge by a face; sorting these groups the uses of each edge.
struct EdgeUse {
  uint64_t key;  // (larger vertex << 32) | smaller vertex
  int face;
  bool forward;  // traversed from the smaller to the larger vertex index
  auto operator<=>(const EdgeUse&) const = default;
};

uint64_t edgeKey(int a, int b) {
  const auto lo = static_cast<uint32_t>(std::min(a, b));
  const auto hi = static_cast<uint32_t>(std::max(a, b));
  return (static_cast<uint64_t>(hi) << 32) | lo;
}

std::string edgeName(uint64_t key) {
  return "(" + std::to_string(key & 0xffffffffu) + ", " + std::to_string(key >> 32) + ")";
}

std::string plural(int n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

TopologyFindings noteTopology(CageMesh& mesh) {
  TopologyFindings found;
  std::vector<char> used(mesh.positions.size(), 0);
  std::vector<EdgeUse> uses;
  uses.reserve(mesh.faceVertices.size());
  std::string firstRepeat;

  size_t offset = 0;
  std::vector<int> sorted;
  for (int f = 0; f < mesh.faceCount(); ++f) {
    const int n = mesh.faceSizes[static_cast<size_t>(f)];
    const int* fv = mesh.faceVertices.data() + offset;
    offset += static_cast<size_t>(n);

    sorted.assign(fv, fv + n);
    std::sort(sorted.begin(), sorted.end());
    if (auto it = std::adjacent_find(sorted.begin(), sorted.end()); it != sorted.end()) {
      if (found.facesRepeatingAVertex++ == 0)
        firstRepeat =
            "face " + std::to_string(f) + " uses vertex " + std::to_string(*it) + " twice";
    }
    for (int k = 0; k < n; ++k) {
      const int a = fv[k];
      const int b = fv[(k + 1) % n];
      used[static_cast<size_t>(a)] = 1;
      if (a == b) continue;  // a collapsed edge of a face that repeats a vertex
      uses.push_back({edgeKey(a, b), f, a < b});
    }
  }

  // Walk the uses edge by edge (in key order, so the example named is the smallest edge).
  std::sort(uses.begin(), uses.end());
  uint64_t firstManyFaces = UINT64_MAX, firstConflict = UINT64_MAX;
  int firstManyFacesCount = 0;
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    int faces = 0, forward = 0, backward = 0;
    for (; j < uses.size() && uses[j].key == uses[i].key; ++j) {
      faces += j == i || uses[j].face != uses[j - 1].face;  // a face counts once per edge
      (uses[j].forward ? forward : backward) += 1;
    }
    if (faces > 2 && found.edgesWithManyFaces++ == 0) {
      firstManyFaces = uses[i].key;
      firstManyFacesCount = faces;
    }
    // Orientation is only defined across a manifold edge: its two faces must traverse it in
    // opposite directions.
    if (faces == 2 && (forward > 1 || backward > 1) && found.orientationConflicts++ == 0)
      firstConflict = uses[i].key;
    i = j;
  }
  int firstUnused = -1;
  for (size_t v = 0; v < used.size(); ++v)
    if (!used[v] && found.unusedVertices++ == 0) firstUnused = static_cast<int>(v);

  if (found.facesRepeatingAVertex)
    mesh.notes.push_back(plural(found.facesRepeatingAVertex, "face repeats", "faces repeat") +
                         " a vertex (first: " + firstRepeat + "); passed to OpenSubdiv as is");
  if (found.unusedVertices)
    mesh.notes.push_back(plural(found.unusedVertices, "vertex is", "vertices are") +
                         " used by no face (first: vertex " + std::to_string(firstUnused) + ")");
  if (found.edgesWithManyFaces)
    mesh.notes.push_back(plural(found.edgesWithManyFaces, "edge is", "edges are") +
                         " shared by more than two faces (non-manifold; first: edge " +
                         edgeName(firstManyFaces) + " with " + std::to_string(firstManyFacesCount) +
                         " faces)");
  if (found.orientationConflicts)
    mesh.notes.push_back(
        plural(found.orientationConflicts, "edge is", "edges are") +
        " traversed twice in the same direction (inconsistent orientation; first: edge " +
        edgeName(firstConflict) + ")");
  return found;
}

}  // namespace osd_cull::adapters
