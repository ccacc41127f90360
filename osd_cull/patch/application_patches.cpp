#include "osd_cull/patch/application_patches.h"

#include "osd_cull/error.h"
#include "osd_cull/patch/bspline_bezier.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace osd_cull {

PatchPointMatrix patchPointMatrix(const Far::PatchTable& table, int refinedVertexCount) {
  const int columns = refinedVertexCount + table.GetNumLocalPoints();
  const PatchOrder order = patchOrder(table, "patchPointMatrix");
  std::vector<int> sizes, indices;
  std::vector<double> weights;
  std::vector<std::pair<int, double>> row;
  for (const PatchRef& ref : order.bezier) {
    const Far::ConstIndexArray cvs = table.GetPatchVertices(ref.array, ref.index);
    const PatchConversion& conversion =
        bsplineToBezierWeights(table.GetPatchParam(ref.array, ref.index).GetBoundary());
    for (std::size_t r = 0; r < 16; ++r) {
      // Boundary patches repeat point indices: sum their weights into one entry.
      row.clear();
      for (std::size_t k = 0; k < 16; ++k)
        if (conversion[r][k] != 0.0) row.emplace_back(cvs[static_cast<int>(k)], conversion[r][k]);
      std::sort(row.begin(), row.end());
      int size = 0;
      for (std::size_t e = 0; e < row.size(); ++e) {
        if (size > 0 && indices.back() == row[e].first) {
          weights.back() += row[e].second;
          continue;
        }
        indices.push_back(row[e].first);
        weights.push_back(row[e].second);
        ++size;
      }
      sizes.push_back(size);
    }
  }
  for (const PatchRef& ref : order.gregory)
    for (const Far::Index point : table.GetPatchVertices(ref.array, ref.index)) {
      sizes.push_back(1);
      indices.push_back(point);
      weights.push_back(1.0);
    }
  return PatchPointMatrix(columns, std::move(sizes), std::move(indices), std::move(weights));
}

ApplicationPatches extractApplicationPatches(const Far::TopologyRefiner& refiner,
                                             const Far::PatchTable& table,
                                             std::span<const glm::dvec3> cage,
                                             const std::string& source,
                                             std::span<const glm::dvec2> uvs) {
  const std::string where = source.empty() ? std::string("application mesh") : source;
  AdaptivePatches adopted;
  try {
    adopted = adoptPatchTable(refiner, table);
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  ApplicationPatches out;
  out.extraction = extractPatches(refiner, adopted, cage, where, uvs);
  out.extraction.patches.source = source;
  out.fromPatchPoints = patchPointMatrix(table, refiner.GetNumVerticesTotal());
  return out;
}

}  // namespace osd_cull
