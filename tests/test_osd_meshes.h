#pragma once
// An open cage built in code for the Osd backend tests (osd_cull/scene/procedural.h has
// the closed ones), and small comparison helpers.
#include "osd_cull/patch/cage_mesh.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

namespace osd_cull::test {

/// A ring of quads around a valence-6 pole with a triangle and an open boundary: regular,
/// boundary and extraordinary patches in one cage.
inline CageMesh openFan() {
  CageMesh m;
  m.source = "built-in:open-fan";
  m.positions.push_back({0, 0, 0.5});
  constexpr int kSpokes = 6;
  for (int ring = 1; ring <= 2; ++ring)
    for (int i = 0; i < 2 * kSpokes; ++i) {
      const double a = 3.14159265358979 * i / kSpokes;
      m.positions.push_back({ring * std::cos(a), ring * std::sin(a), 0.3 * ring * std::sin(3 * a)});
    }
  auto inner = [](int i) { return 1 + (i % 12); };
  auto outer = [](int i) { return 13 + (i % 12); };
  for (int s = 0; s < kSpokes - 1; ++s) {  // five quads at the pole, one triangle
    m.faceSizes.push_back(4);
    m.faceVertices.insert(m.faceVertices.end(),
                          {0, inner(2 * s), inner(2 * s + 1), inner(2 * s + 2)});
  }
  m.faceSizes.push_back(3);
  m.faceVertices.insert(m.faceVertices.end(), {0, inner(10), inner(12)});
  m.faceSizes.push_back(3);
  m.faceVertices.insert(m.faceVertices.end(), {inner(10), inner(11), inner(12)});
  for (int i = 0; i < 12; ++i) {
    m.faceSizes.push_back(4);
    m.faceVertices.insert(m.faceVertices.end(), {inner(i), outer(i), outer(i + 1), inner(i + 1)});
  }
  return m;
}

/// Cage positions as packed xyz floats (what Osd::Mesh::UpdateVertexBuffer takes).
inline std::vector<float> packedXyz(const CageMesh& m) {
  std::vector<float> out;
  for (const glm::dvec3& p : m.positions)
    out.insert(out.end(),
               {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
  return out;
}

/// Diagonal of the bounding box of packed xyz values.
inline double boxDiagonal(std::span<const double> xyz) {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (size_t i = 0; i + 2 < xyz.size(); i += 3) {
    lo = glm::min(lo, glm::dvec3(xyz[i], xyz[i + 1], xyz[i + 2]));
    hi = glm::max(hi, glm::dvec3(xyz[i], xyz[i + 1], xyz[i + 2]));
  }
  return glm::length(hi - lo);
}

/// Largest absolute difference of two equally long arrays (infinity if lengths differ).
template <class A, class B>
double maxAbsDifference(const std::vector<A>& a, const std::vector<B>& b) {
  if (a.size() != b.size()) return INFINITY;
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, std::abs(static_cast<double>(a[i]) - static_cast<double>(b[i])));
  return worst;
}

}  // namespace osd_cull::test
