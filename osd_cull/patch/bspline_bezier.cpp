#include "osd_cull/patch/bspline_bezier.h"

#include <algorithm>

namespace osd_cull {
namespace {

// A B-spline point expressed as weights of the 16 stored points, so the extrapolation and
// the conversion can run once symbolically and give the linear map.
struct Combination {
  std::array<double, 16> w{};
  friend Combination operator*(double s, const Combination& c) {
    Combination r;
    for (int k = 0; k < 16; ++k) r.w[k] = s * c.w[k];
    return r;
  }
  friend Combination operator-(const Combination& a, const Combination& b) {
    Combination r;
    for (int k = 0; k < 16; ++k) r.w[k] = a.w[k] - b.w[k];
    return r;
  }
  friend Combination operator+(const Combination& a, const Combination& b) {
    Combination r;
    for (int k = 0; k < 16; ++k) r.w[k] = a.w[k] + b.w[k];
    return r;
  }
};

// OsdComputeBSplineBoundaryPoints (osd/glslPatchCommon.glsl), statement for statement.
// The edge points are extrapolated first; the corner points only afterwards, because they
// are extrapolated from edge points that may themselves have been replaced.
template <class T>
void extrapolate(T* cpt, unsigned mask) {
  if (mask & 1u) {
    cpt[1] = 2.0 * cpt[5] - cpt[9];
    cpt[2] = 2.0 * cpt[6] - cpt[10];
  }
  if (mask & 2u) {
    cpt[7] = 2.0 * cpt[6] - cpt[5];
    cpt[11] = 2.0 * cpt[10] - cpt[9];
  }
  if (mask & 4u) {
    cpt[13] = 2.0 * cpt[9] - cpt[5];
    cpt[14] = 2.0 * cpt[10] - cpt[6];
  }
  if (mask & 8u) {
    cpt[4] = 2.0 * cpt[5] - cpt[6];
    cpt[8] = 2.0 * cpt[9] - cpt[10];
  }
  if (mask & 1u) {
    cpt[0] = 2.0 * cpt[4] - cpt[8];
    cpt[3] = 2.0 * cpt[7] - cpt[11];
  }
  if (mask & 2u) {
    cpt[3] = 2.0 * cpt[2] - cpt[1];
    cpt[15] = 2.0 * cpt[14] - cpt[13];
  }
  if (mask & 4u) {
    cpt[12] = 2.0 * cpt[8] - cpt[4];
    cpt[15] = 2.0 * cpt[11] - cpt[7];
  }
  if (mask & 8u) {
    cpt[0] = 2.0 * cpt[1] - cpt[2];
    cpt[12] = 2.0 * cpt[13] - cpt[14];
  }
}

// Cubic B-spline → Bézier in one direction (the matrix Q of OsdComputePerPatchVertexBSpline):
// Bézier point i = sum over k of kQ[i][k] * B-spline point k.
constexpr double kQ[4][4] = {{1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0},
                             {0.0, 4.0 / 6.0, 2.0 / 6.0, 0.0},
                             {0.0, 2.0 / 6.0, 4.0 / 6.0, 0.0},
                             {0.0, 1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0}};

// Tensor-product conversion of 16 points (row l = v index, u fastest), as in the shader:
// first along u within each row, then along v.
template <class T>
std::array<T, 16> convert(const T* cv) {
  std::array<T, 16> out{};
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {
      T p{};
      for (int l = 0; l < 4; ++l) {
        T h{};
        for (int k = 0; k < 4; ++k)
          if (kQ[i][k] != 0.0) h = h + kQ[i][k] * cv[4 * l + k];
        if (kQ[j][l] != 0.0) p = p + kQ[j][l] * h;
      }
      out[4 * j + i] = p;
    }
  }
  return out;
}

std::array<PatchConversion, 16> buildConversionTable() {
  std::array<PatchConversion, 16> table{};
  for (unsigned mask = 0; mask < 16; ++mask) {
    std::array<Combination, 16> cv{};
    for (int k = 0; k < 16; ++k) cv[k].w[k] = 1.0;
    extrapolate(cv.data(), mask);
    const std::array<Combination, 16> bezier = convert(cv.data());
    for (int r = 0; r < 16; ++r) table[mask][r] = bezier[r].w;
  }
  return table;
}

}  // namespace

void extrapolateBoundaryPoints(std::span<glm::dvec3, 16> points, unsigned boundaryMask) {
  extrapolate(points.data(), boundaryMask & 15u);
}

const PatchConversion& bsplineToBezierWeights(unsigned boundaryMask) {
  static const std::array<PatchConversion, 16> table = buildConversionTable();
  return table[boundaryMask & 15u];
}

std::array<glm::dvec3, 16> bsplineToBezier(std::span<const glm::dvec3, 16> points,
                                           unsigned boundaryMask) {
  std::array<glm::dvec3, 16> cv;
  std::copy(points.begin(), points.end(), cv.begin());
  extrapolate(cv.data(), boundaryMask & 15u);
  return convert(cv.data());
}

}  // namespace osd_cull
