#pragma once
/// \file test_patch_support.h
/// \brief Shared by the tests/test_patch_*.cpp suites: cages built in code, OpenSubdiv's own
/// limit-surface evaluation as the reference, and the comparison of a PatchSet against it.

#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/patch_eval.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/procedural.h"

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace osd_cull::test {

// ---------------------------------------------------------------------------------------
// Open cages built in code (closed ones come from osd_cull/scene/procedural.h)
// ---------------------------------------------------------------------------------------

/// An open disk of `valence` quads around a centre vertex (a pole of that valence), with a
/// second ring of quads outside so the pole is away from the boundary. Boundary and
/// boundary-corner patches appear on the rim.
inline CageMesh poleCage(int valence) {
  CageMesh m;
  m.source = "built-in:pole" + std::to_string(valence);
  m.positions.push_back({0, 0, 0.3});
  const int ring = 2 * valence;  // ring 1: spokes and face midpoints alternate
  for (int r = 1; r <= 2; ++r)
    for (int k = 0; k < ring; ++k) {
      const double a = 2.0 * std::numbers::pi * k / ring;
      const double radius = r * (k % 2 == 0 ? 1.0 : 1.1);
      m.positions.push_back(
          {radius * std::cos(a), radius * std::sin(a), 0.1 * std::sin(3.0 * a) * r});
    }
  auto ring1 = [&](int k) { return 1 + (k % ring + ring) % ring; };
  auto ring2 = [&](int k) { return 1 + ring + (k % ring + ring) % ring; };
  for (int f = 0; f < valence; ++f) {
    const int k = 2 * f;
    m.faceSizes.push_back(4);
    m.faceVertices.insert(m.faceVertices.end(), {0, ring1(k), ring1(k + 1), ring1(k + 2)});
  }
  for (int k = 0; k < ring; ++k) {
    m.faceSizes.push_back(4);
    m.faceVertices.insert(m.faceVertices.end(), {ring1(k), ring2(k), ring2(k + 1), ring1(k + 1)});
  }
  return m;
}

/// A flat-ish open grid of n x n quads with a bump: regular, boundary and corner patches.
inline CageMesh gridCage(int n = 4) {
  CageMesh m;
  m.source = "built-in:grid";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.positions.push_back({double(i), double(j), 0.3 * std::sin(1.3 * i) * std::cos(0.7 * j)});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.faceSizes.push_back(4);
      const int a = j * (n + 1) + i;
      m.faceVertices.insert(m.faceVertices.end(), {a, a + 1, a + n + 2, a + n + 1});
    }
  return m;
}

// ---------------------------------------------------------------------------------------
// OpenSubdiv's own evaluation (the reference)
// ---------------------------------------------------------------------------------------

/// A primvar for Far's stencil tables.
struct RefPoint {
  glm::dvec3 p{0.0};
  void Clear(void* = nullptr) { p = glm::dvec3(0.0); }
  void AddWithWeight(const RefPoint& src, double w) { p += w * src.p; }
};

/// The limit surface as OpenSubdiv evaluates it: Far::PatchTable built from its own refiner
/// with the same options, control values from StencilTable::UpdateValues and the local-point
/// stencils (the double-precision ComputeLocalPointValues), PatchMap to find the patch of a
/// (face, u, v), PatchTable::EvaluateBasis for the weights.
class OsdReference {
 public:
  OsdReference(const CageMesh& cage, const PatchOptions& options) {
    refiner_ = makeTopologyRefiner(cage);
    Far::PatchTableFactory::Options po(static_cast<unsigned>(options.isolationLevel));
    po.SetEndCapType(options.endCaps == EndCap::BSplineBasis
                         ? Far::PatchTableFactory::Options::ENDCAP_BSPLINE_BASIS
                         : Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
    po.useInfSharpPatch = options.infSharpPatches;
    po.SetPatchPrecision<double>();
    Far::TopologyRefiner::AdaptiveOptions ao = po.GetRefineAdaptiveOptions();
    if (options.secondaryLevel) ao.SetSecondaryLevel(*options.secondaryLevel);
    refiner_->RefineAdaptive(ao);
    table_.reset(Far::PatchTableFactory::Create(*refiner_, po));
    Far::StencilTableFactoryReal<double>::Options so;
    so.generateControlVerts = true;
    so.generateIntermediateLevels = true;
    so.generateOffsets = true;
    stencils_.reset(Far::StencilTableFactoryReal<double>::Create(*refiner_, so));
    map_ = std::make_unique<Far::PatchMap>(*table_);
    setCage(cage.positions);
  }

  /// Recomputes all control values from new cage positions.
  void setCage(const std::vector<glm::dvec3>& cage) {
    std::vector<RefPoint> src(cage.size());
    for (size_t i = 0; i < cage.size(); ++i) src[i].p = cage[i];
    const int refined = refiner_->GetNumVerticesTotal();
    values_.assign(static_cast<size_t>(refined + table_->GetNumLocalPoints()), RefPoint{});
    stencils_->UpdateValues(src.data(), values_.data());
    if (const auto* local = table_->GetLocalPointStencilTable<double>();
        local && local->GetNumStencils() > 0)
      local->UpdateValues(values_.data(), values_.data() + refined);
  }

  /// Position and derivatives at local (s, t) of the patch with PatchParam `param`;
  /// derivatives with respect to the patch's own parameters (Far's divided by 2^depth).
  /// Returns false when PatchMap finds no patch there.
  bool evaluate(const Far::PatchParam& param, double s, double t, SurfacePoint& out) const {
    double u = s, v = t;
    param.Unnormalize(u, v);
    const Far::PatchTable::PatchHandle* h = map_->FindPatch(param.GetFaceId(), u, v);
    if (!h) return false;
    double w[20], wu[20], wv[20];
    table_->EvaluateBasis(*h, u, v, w, wu, wv);
    const Far::ConstIndexArray cvs = table_->GetPatchVertices(*h);
    const double scale = 1.0 / static_cast<double>(1 << table_->GetPatchParam(*h).GetDepth());
    out = SurfacePoint{};
    for (int k = 0; k < cvs.size(); ++k) {
      const glm::dvec3& p = values_[static_cast<size_t>(cvs[k])].p;
      out.position += w[k] * p;
      out.du += wu[k] * scale * p;
      out.dv += wv[k] * scale * p;
    }
    return true;
  }

  const Far::PatchTable& patchTable() const { return *table_; }

 private:
  std::unique_ptr<Far::TopologyRefiner> refiner_;
  std::unique_ptr<const Far::PatchTable> table_;
  std::unique_ptr<const Far::StencilTableReal<double>> stencils_;
  std::unique_ptr<Far::PatchMap> map_;
  std::vector<RefPoint> values_;
};

/// Diagonal of the axis-aligned bounding box of some points.
inline double boundingDiagonal(const std::vector<glm::dvec3>& points) {
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const glm::dvec3& p : points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return glm::length(hi - lo);
}

/// Largest deviations of a PatchSet from the reference, in absolute units.
struct Deviation {
  double position = 0.0;
  double derivative = 0.0;
  size_t samples = 0;
  size_t unmatched = 0;  ///< samples PatchMap could not place (should be 0)
  std::string worst;     ///< where the largest deviation was
};

/// Samples each patch at `perPatch` random interior (u, v) (fewer if the total would pass
/// `cap`, at least 4) and compares position and derivatives with the reference.
inline Deviation compareWithReference(const PatchSet& set, const OsdReference& ref, uint32_t seed,
                                      int perPatch = 64, size_t cap = 40000) {
  Deviation d;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(1e-3, 1.0 - 1e-3);
  const size_t patches = std::max<size_t>(1, set.patchCount());
  const int n =
      static_cast<int>(std::clamp<size_t>(cap / patches, 4, static_cast<size_t>(perPatch)));
  for (uint32_t p = 0; p < set.patchCount(); ++p) {
    for (int k = 0; k < n; ++k) {
      // The corners are sampled too: they are where Gregory and boundary logic differ most.
      const double s = k == 0 ? 0.0 : k == 1 ? 1.0 : uni(rng);
      const double t = k == 0 ? 0.0 : k == 1 ? 1.0 : uni(rng);
      // At the corners PatchMap may pick a neighbour patch; evaluate a hair inside instead.
      const double si = std::clamp(s, 1e-9, 1.0 - 1e-9), ti = std::clamp(t, 1e-9, 1.0 - 1e-9);
      SurfacePoint theirs;
      if (!ref.evaluate(set.params[p], si, ti, theirs)) {
        ++d.unmatched;
        continue;
      }
      const SurfacePoint ours = evaluatePatch(set, p, si, ti);
      ++d.samples;
      const double ep = glm::length(ours.position - theirs.position);
      const double ed =
          std::max(glm::length(ours.du - theirs.du), glm::length(ours.dv - theirs.dv));
      if (ep > d.position || ed > d.derivative)
        d.worst = "patch " + std::to_string(p) + " (face " +
                  std::to_string(set.params[p].GetFaceId()) + ", depth " +
                  std::to_string(set.params[p].GetDepth()) + ", boundary " +
                  std::to_string(set.params[p].GetBoundary()) + ") at (" + std::to_string(si) +
                  ", " + std::to_string(ti) + ")";
      d.position = std::max(d.position, ep);
      d.derivative = std::max(d.derivative, ed);
    }
  }
  return d;
}

/// Largest |row sum - 1| of a matrix (0 for an empty matrix).
inline double maxRowSumError(const PatchPointMatrix& m) {
  double worst = 0.0;
  const auto sizes = m.sizes();
  const auto weights = m.weights();
  size_t e = 0;
  for (int size : sizes) {
    double sum = 0.0;
    for (int k = 0; k < size; ++k) sum += weights[e++];
    worst = std::max(worst, std::abs(sum - 1.0));
  }
  return worst;
}

/// The cage with every vertex moved by a random offset of up to `amount` per axis.
inline std::vector<glm::dvec3> jitter(const std::vector<glm::dvec3>& cage, double amount,
                                      uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(-amount, amount);
  std::vector<glm::dvec3> out = cage;
  for (glm::dvec3& p : out) p += glm::dvec3(uni(rng), uni(rng), uni(rng));
  return out;
}

}  // namespace osd_cull::test
