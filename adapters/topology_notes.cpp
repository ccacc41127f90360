#include "adapters/topology_notes.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace osd_cull::adapters {
namespace {

struct EdgeUse {
  int faces = 0;     // faces that have this edge
  int forward = 0;   // traversals from the smaller to the larger vertex index
  int backward = 0;  // traversals from the larger to the smaller
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
  std::unordered_map<uint64_t, EdgeUse> edges;
  edges.reserve(mesh.faceVertices.size());
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
    // Count each distinct edge of a face once, however often the face repeats it.
    std::vector<uint64_t> seen;
    for (int k = 0; k < n; ++k) {
      const int a = fv[k];
      const int b = fv[(k + 1) % n];
      used[static_cast<size_t>(a)] = 1;
      if (a == b) continue;  // a collapsed edge of a face that repeats a vertex
      const uint64_t key = edgeKey(a, b);
      EdgeUse& use = edges[key];
      (a < b ? use.forward : use.backward) += 1;
      if (std::find(seen.begin(), seen.end(), key) == seen.end()) {
        seen.push_back(key);
        ++use.faces;
      }
    }
  }

  // The example named is the smallest edge key, so notes do not depend on hash order.
  uint64_t firstManyFaces = UINT64_MAX, firstConflict = UINT64_MAX;
  for (const auto& [key, use] : edges) {
    if (use.faces > 2) {
      ++found.edgesWithManyFaces;
      firstManyFaces = std::min(firstManyFaces, key);
    }
    // Orientation is only defined across a manifold edge: its two faces must traverse it in
    // opposite directions.
    if (use.faces == 2 && (use.forward > 1 || use.backward > 1)) {
      ++found.orientationConflicts;
      firstConflict = std::min(firstConflict, key);
    }
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
                         edgeName(firstManyFaces) + " with " +
                         std::to_string(edges[firstManyFaces].faces) + " faces)");
  if (found.orientationConflicts)
    mesh.notes.push_back(
        plural(found.orientationConflicts, "edge is", "edges are") +
        " traversed twice in the same direction (inconsistent orientation; first: edge " +
        edgeName(firstConflict) + ")");
  return found;
}

}  // namespace osd_cull::adapters
