#include "osd_cull/frame/draw/tess_levels.h"

#include "osd_cull/error.h"

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace osd_cull::frame {

namespace {

constexpr std::array<uint32_t, 4> kTransitionBit = {8u, 1u, 2u, 4u};

bool toPixels(const glm::dvec3& p, const glm::dmat4& vp, const glm::dvec2& viewport,
              glm::dvec2& pixel) {
  const glm::dvec4 c = vp * glm::dvec4(p, 1.0);
  pixel = glm::dvec2(c) / c.w * 0.5 * viewport;
  return c.w > 1e-6;
}

// Pixels per object unit of a short vector at p in any direction, to first order: the
// projection's Jacobian 0.5 v (r_i - (c_i / w) r_3) / w, bounded by the norms of the rows
// r_i of the linear part (the shader's pixelScale()).
double pixelScale(const glm::dvec3& p, const glm::dmat4& vp, const glm::dvec2& viewport) {
  const glm::dvec4 c = vp * glm::dvec4(p, 1.0);
  const auto row = [&](int i) { return glm::length(glm::dvec3(vp[0][i], vp[1][i], vp[2][i])); };
  const double r3 = row(3);
  return 0.5 *
         std::max(viewport.x * (row(0) + std::abs(c.x / c.w) * r3),
                  viewport.y * (row(1) + std::abs(c.y / c.w) * r3)) /
         c.w;
}

// `offset`: the displacement's variation along the curve (object units), added at the
// largest pixel scale of the curve's control points.
double curveLevel(const std::array<glm::dvec3, 4>& b, double offset, const glm::dmat4& vp,
                  const glm::dvec2& viewport, double pixelsPerSegment, double maxLevel) {
  std::array<glm::dvec2, 4> s;
  bool ok = true;
  for (int i = 0; i < 4; ++i) ok = toPixels(b[i], vp, viewport, s[i]) && ok;
  if (!ok) return maxLevel;
  double len = (glm::distance(s[0], s[1]) + glm::distance(s[2], s[3])) + glm::distance(s[1], s[2]);
  if (offset > 0.0)
    len +=
        offset * std::max(std::max(pixelScale(b[0], vp, viewport), pixelScale(b[1], vp, viewport)),
                          std::max(pixelScale(b[2], vp, viewport), pixelScale(b[3], vp, viewport)));
  const double level = std::ceil(len / pixelsPerSegment);
  if (!(level >= 1.0)) return level < 1.0 ? 1.0 : maxLevel;
  return std::min(level, maxLevel);
}

}  // namespace

const char* toString(DisplacedTessellation mode) {
  switch (mode) {
    case DisplacedTessellation::Ignore:
      return "none";
    case DisplacedTessellation::PerPatch:
      return "per-patch";
    case DisplacedTessellation::EdgeVariation:
      break;
  }
  return "edge";
}

uint32_t PatchTessLevels::vertexCount() const {
  double o[4], in[2] = {std::ceil(inner(0)), std::ceil(inner(1))};
  bool allOne = in[0] <= 1.0 && in[1] <= 1.0;
  for (int e = 0; e < 4; ++e) {
    o[e] = std::max(1.0, std::ceil(outer(e)));
    allOne = allOne && o[e] == 1.0;
  }
  if (allOne) return 4;
  for (double& i : in) i = std::max(i, 2.0);
  return static_cast<uint32_t>((in[0] - 1.0) * (in[1] - 1.0) + o[0] + o[1] + o[2] + o[3]);
}

bool hasTransitionEdges(const PatchSet& patches) {
  for (const auto& p : patches.params)
    if (p.GetTransition() != 0) return true;
  return false;
}

TessellationOptions effectiveOptions(const TessellationOptions& options, bool transitionEdges) {
  TessellationOptions out = options;
  if (transitionEdges) out.uniformLevel = std::min(out.uniformLevel, options.maxLevel / 2);
  return out;
}

std::array<std::array<uint32_t, 4>, 4> edgeCurveIndices(PatchType type) {
  if (type == PatchType::Bezier)
    return {{{0, 4, 8, 12}, {0, 1, 2, 3}, {3, 7, 11, 15}, {12, 13, 14, 15}}};
  return {{{0, 2, 16, 15}, {0, 1, 7, 5}, {5, 6, 12, 10}, {15, 17, 11, 10}}};
}

std::vector<EdgeDisplacement> edgeDisplacements(const bound::DisplacementMap& map,
                                                std::span<const glm::dvec2> uvCorners,
                                                uint32_t patchCount) {
  if (uvCorners.size() != 4 * size_t{patchCount})
    throw Error("displacement map " + map.name() + ": " + std::to_string(uvCorners.size()) +
                " texture coordinates for " + std::to_string(patchCount) +
                " patches (4 per patch expected)");
  // Edge e runs from corner kFrom[e] to kTo[e] (corners (0,0), (1,0), (1,1), (0,1)), in
  // the direction of its boundary curve (edgeCurveIndices).
  constexpr std::array<int, 4> kFrom = {0, 0, 1, 3}, kTo = {3, 1, 2, 2};
  std::vector<EdgeDisplacement> out(patchCount);
  const auto asFloat = [](glm::dvec2 v) {
    return glm::dvec2(static_cast<float>(v.x), static_cast<float>(v.y));
  };
  const auto roundUp = [](double v) {
    const auto f = static_cast<float>(v);
    return double(f) < v ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
  };
  for (uint32_t p = 0; p < patchCount; ++p)
    for (int e = 0; e < 4; ++e) {
      const glm::dvec2 a = asFloat(uvCorners[4 * size_t{p} + kFrom[e]]);
      const glm::dvec2 b = asFloat(uvCorners[4 * size_t{p} + kTo[e]]);
      const glm::dvec2 m = asFloat(0.5 * (a + b));  // the finer neighbour's corner
      out[p].whole[e] = roundUp(map.variationAlong(a, b));
      out[p].firstHalf[e] = roundUp(map.variationAlong(a, m));
      out[p].secondHalf[e] = roundUp(map.variationAlong(m, b));
    }
  return out;
}

void edgeDisplacementTerms(const EdgeDisplacement& d, DisplacedTessellation mode,
                           const std::array<bool, 4>& split, std::array<double, 4>& lo,
                           std::array<double, 4>& hi) {
  const float largest =
      std::max(std::max(d.whole[0], d.whole[1]), std::max(d.whole[2], d.whole[3]));
  for (int e = 0; e < 4; ++e) {
    switch (mode) {
      case DisplacedTessellation::Ignore:
        lo[e] = hi[e] = 0.0;
        break;
      case DisplacedTessellation::PerPatch:
        lo[e] = hi[e] = largest;
        break;
      case DisplacedTessellation::EdgeVariation:
        lo[e] = split[e] ? d.firstHalf[e] : d.whole[e];
        hi[e] = split[e] ? d.secondHalf[e] : 0.0;
        break;
    }
  }
}

PatchTessLevels patchTessLevels(const PatchSet& patches, uint32_t patch,
                                const glm::dmat4& viewProjection, const glm::dvec2& viewport,
                                const TessellationOptions& options,
                                const EdgeDisplacement* displacement) {
  PatchTessLevels out;
  const auto cp = patches.controlPoints(patch);
  const auto curves = edgeCurveIndices(patches.type(patch));
  const uint32_t transition = patches.params[patch].GetTransition();
  const double maxLevel = options.maxLevel;
  const double half = std::floor(maxLevel * 0.5);
  std::array<bool, 4> splits{};
  for (int e = 0; e < 4; ++e) splits[e] = (transition & kTransitionBit[e]) != 0;
  std::array<double, 4> offsetLo{}, offsetHi{};
  if (displacement)
    edgeDisplacementTerms(*displacement, options.displaced, splits, offsetLo, offsetHi);
  for (int e = 0; e < 4; ++e) {
    const bool split = splits[e];
    std::array<glm::dvec3, 4> b;
    for (int i = 0; i < 4; ++i) b[i] = cp[curves[e][i]];
    if (options.mode == TessellationOptions::Mode::Uniform) {
      const double level = std::min<double>(options.uniformLevel, split ? half : maxLevel);
      out.lo[e] = level;
      out.hi[e] = split ? level : 0.0;
    } else if (!split) {
      out.lo[e] =
          curveLevel(b, offsetLo[e], viewProjection, viewport, options.pixelsPerSegment, half);
    } else {
      const glm::dvec3 b01 = 0.5 * (b[0] + b[1]), b12 = 0.5 * (b[1] + b[2]),
                       b23 = 0.5 * (b[2] + b[3]);
      const glm::dvec3 b012 = 0.5 * (b01 + b12), b123 = 0.5 * (b12 + b23);
      const glm::dvec3 m = 0.5 * (b012 + b123);
      out.lo[e] = curveLevel({b[0], b01, b012, m}, offsetLo[e], viewProjection, viewport,
                             options.pixelsPerSegment, half);
      out.hi[e] = curveLevel({m, b123, b23, b[3]}, offsetHi[e], viewProjection, viewport,
                             options.pixelsPerSegment, half);
    }
  }
  return out;
}

std::vector<uint32_t> tessVertexBounds(const PatchSet& patches, const glm::dmat4& viewProjection,
                                       const glm::dvec2& viewport,
                                       const TessellationOptions& requested,
                                       std::span<const EdgeDisplacement> displacement) {
  const TessellationOptions options = effectiveOptions(requested, hasTransitionEdges(patches));
  if (!displacement.empty() && displacement.size() != patches.patchCount())
    throw Error("tessVertexBounds: " + std::to_string(displacement.size()) +
                " edge displacements for " + std::to_string(patches.patchCount()) + " patches");
  std::vector<uint32_t> bounds(patches.patchCount());
  const bool adaptive = options.mode == TessellationOptions::Mode::Adaptive;
  for (uint32_t p = 0; p < patches.patchCount(); ++p) {
    PatchTessLevels levels = patchTessLevels(patches, p, viewProjection, viewport, options,
                                             displacement.empty() ? nullptr : &displacement[p]);
    if (adaptive) {
      // fp32 in the shader may round a level up by one where double did not.
      const double half = std::floor(options.maxLevel * 0.5);
      for (int e = 0; e < 4; ++e) {
        levels.lo[e] = std::min(levels.lo[e] + 1.0, half);
        if (levels.hi[e] > 0.0) levels.hi[e] = std::min(levels.hi[e] + 1.0, half);
      }
    }
    bounds[p] = levels.vertexCount();
  }
  return bounds;
}

std::vector<bound::TriangleShape> drawnTriangleShapes(const PatchSet& patches,
                                                      const glm::dmat4& viewProjection,
                                                      const glm::dvec2& viewport,
                                                      const TessellationOptions& requested) {
  const TessellationOptions options = effectiveOptions(requested, hasTransitionEdges(patches));
  const double slack = options.mode == TessellationOptions::Mode::Adaptive ? 1.0 : 0.0;
  std::vector<bound::TriangleShape> shapes(patches.patchCount());
  for (uint32_t p = 0; p < patches.patchCount(); ++p) {
    // Gregory patches too: the bound never culls them, the listed triangles (exact levels) can.
    const PatchTessLevels levels = patchTessLevels(patches, p, viewProjection, viewport, options);
    shapes[p] = bound::triangleShape({levels.lo, levels.hi}, slack);
  }
  return shapes;
}

std::vector<bound::TriangleShape> drawnTriangleShapes(std::span<const PatchTessLevels> levels) {
  std::vector<bound::TriangleShape> shapes(levels.size());
  for (size_t p = 0; p < levels.size(); ++p)
    shapes[p] = bound::triangleShape({levels[p].lo, levels[p].hi}, 0.0);
  return shapes;
}

}  // namespace osd_cull::frame
