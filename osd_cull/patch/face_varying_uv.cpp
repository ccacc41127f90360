#include "osd_cull/patch/face_varying_uv.h"

#include "osd_cull/error.h"
#include "osd_cull/patch/patch_eval.h"

#include <opensubdiv/far/primvarRefiner.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

namespace osd_cull {
namespace {

// A face-varying value as Far::PrimvarRefiner wants it.
struct UV {
  glm::dvec2 st{0.0};
  void Clear() { st = glm::dvec2(0.0); }
  void AddWithWeight(const UV& src, double weight) { st += weight * src.st; }
};

constexpr std::array<glm::dvec2, 4> kCorners = {glm::dvec2(0, 0), glm::dvec2(1, 0),
                                                glm::dvec2(1, 1), glm::dvec2(0, 1)};

}  // namespace

PatchUVEvaluator::PatchUVEvaluator(const Far::TopologyRefiner& refiner,
                                   const Far::PatchTable& table, std::span<const glm::dvec2> uvs,
                                   const std::string& where)
    : table_(table) {
  if (table.GetNumFVarChannels() < 1 || refiner.GetNumFVarChannels() < 1)
    throw Error(where + ": the patch table has no face-varying channel for texture coordinates");
  if (static_cast<int>(uvs.size()) != refiner.GetLevel(0).GetNumFVarValues(0))
    throw Error(where + ": " + std::to_string(uvs.size()) +
                " texture coordinates for a face-varying channel of " +
                std::to_string(refiner.GetLevel(0).GetNumFVarValues(0)) + " values");
  if (table.GetFVarPatchDescriptor(0).GetNumControlVertices() != 4 ||
      table.GetNumLocalPointsFaceVarying(0) != 0)
    throw Error(where + ": expected linear face-varying patches (4 values, no local points)");

  std::vector<UV> level(uvs.size());
  for (size_t i = 0; i < uvs.size(); ++i) level[i].st = uvs[i];
  values_.assign(uvs.begin(), uvs.end());
  Far::PrimvarRefinerReal<double> primvar(refiner);
  for (int l = 1; l < refiner.GetNumLevels(); ++l) {
    std::vector<UV> next(static_cast<size_t>(refiner.GetLevel(l).GetNumFVarValues(0)));
    const UV* src = level.data();
    UV* dst = next.data();
    primvar.InterpolateFaceVarying(l, src, dst, 0);
    for (const UV& v : next) values_.push_back(v.st);
    level = std::move(next);
  }
  int first = 0;
  for (int a = 0; a < table.GetNumPatchArrays(); ++a) {
    arrayFirstPatch_.push_back(first);
    first += table.GetNumPatches(a);
  }
}

void PatchUVEvaluator::appendCorners(int array, int index, std::vector<glm::dvec2>& out) const {
  const Far::PatchParam param = table_.GetPatchParam(array, index);
  const Far::ConstIndexArray fv = table_.GetPatchFVarValues(array, index, 0);
  Far::PatchTable::PatchHandle handle;
  handle.arrayIndex = array;
  handle.patchIndex = arrayFirstPatch_[static_cast<size_t>(array)] + index;
  handle.vertIndex = index * table_.GetPatchArrayDescriptor(array).GetNumControlVertices();
  for (glm::dvec2 corner : kCorners) {
    // EvaluateBasisFaceVarying takes base-face coordinates.
    double u = corner.x, v = corner.y;
    param.Unnormalize(u, v);
    double w[4] = {};
    table_.EvaluateBasisFaceVarying(handle, u, v, w);
    glm::dvec2 st(0.0);
    for (int i = 0; i < 4; ++i) st += w[i] * values_.at(static_cast<size_t>(fv[i]));
    out.push_back(st);
  }
}

uint32_t countUVSeamEdges(std::span<const glm::dvec3> positions,
                          std::span<const glm::dvec2> corners) {
  if (positions.size() != corners.size() || positions.size() % 4 != 0)
    throw Error("countUVSeamEdges: positions and texture coordinates must be 4 per patch");
  // Positions are matched after rounding to a grid 1e-9 of the mesh's extent (neighbours
  // compute shared corners from different stencil rows).
  double extent = 1e-300;
  for (const glm::dvec3& p : positions)
    extent = std::max({extent, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  const double cell = extent * 1e-9;
  using Key = std::tuple<int64_t, int64_t, int64_t>;
  const auto key = [&](const glm::dvec3& p) {
    return Key(std::llround(p.x / cell), std::llround(p.y / cell), std::llround(p.z / cell));
  };
  // Per undirected edge: the texture coordinates at its two ends as seen by the first
  // patch; a later patch with other coordinates makes it a seam.
  struct Seen {
    glm::dvec2 a, b;
    bool seam = false;
  };
  std::map<std::pair<Key, Key>, Seen> edges;
  uint32_t seams = 0;
  const double tolerance = 1e-9;
  for (size_t p = 0; p < positions.size(); p += 4)
    for (size_t e = 0; e < 4; ++e) {
      size_t i = p + e, j = p + (e + 1) % 4;
      Key ki = key(positions[i]), kj = key(positions[j]);
      if (kj < ki) {
        std::swap(ki, kj);
        std::swap(i, j);
      }
      auto [it, inserted] = edges.try_emplace({ki, kj}, Seen{corners[i], corners[j]});
      if (inserted || it->second.seam) continue;
      const double d =
          std::max(glm::length(corners[i] - it->second.a), glm::length(corners[j] - it->second.b));
      if (d > tolerance) {
        it->second.seam = true;
        ++seams;
      }
    }
  return seams;
}

uint32_t countUVSeamEdges(const PatchSet& patches, std::span<const glm::dvec2> corners) {
  std::vector<glm::dvec3> positions;
  positions.reserve(4 * size_t{patches.patchCount()});
  for (uint32_t p = 0; p < patches.patchCount(); ++p)
    for (glm::dvec2 st : kCorners)
      positions.push_back(evaluatePatch(patches, p, st.x, st.y).position);
  return countUVSeamEdges(positions, corners);
}

}  // namespace osd_cull
