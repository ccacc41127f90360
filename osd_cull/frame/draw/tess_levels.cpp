#include "osd_cull/frame/draw/tess_levels.h"

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>

namespace osd_cull::frame {

namespace {

constexpr std::array<uint32_t, 4> kTransitionBit = {8u, 1u, 2u, 4u};

bool toPixels(const glm::dvec3& p, const glm::dmat4& vp, const glm::dvec2& viewport,
              glm::dvec2& pixel) {
  const glm::dvec4 c = vp * glm::dvec4(p, 1.0);
  pixel = glm::dvec2(c) / c.w * 0.5 * viewport;
  return c.w > 1e-6;
}

double curveLevel(const std::array<glm::dvec3, 4>& b, const glm::dmat4& vp,
                  const glm::dvec2& viewport, double pixelsPerSegment, double maxLevel) {
  std::array<glm::dvec2, 4> s;
  bool ok = true;
  for (int i = 0; i < 4; ++i) ok = toPixels(b[i], vp, viewport, s[i]) && ok;
  if (!ok) return maxLevel;
  const double len =
      (glm::distance(s[0], s[1]) + glm::distance(s[2], s[3])) + glm::distance(s[1], s[2]);
  const double level = std::ceil(len / pixelsPerSegment);
  if (!(level >= 1.0)) return level < 1.0 ? 1.0 : maxLevel;
  return std::min(level, maxLevel);
}

}  // namespace

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

PatchTessLevels patchTessLevels(const PatchSet& patches, uint32_t patch,
                                const glm::dmat4& viewProjection, const glm::dvec2& viewport,
                                const TessellationOptions& options) {
  PatchTessLevels out;
  const auto cp = patches.controlPoints(patch);
  const auto curves = edgeCurveIndices(patches.type(patch));
  const uint32_t transition = patches.params[patch].GetTransition();
  const double maxLevel = options.maxLevel;
  const double half = std::floor(maxLevel * 0.5);
  for (int e = 0; e < 4; ++e) {
    const bool split = (transition & kTransitionBit[e]) != 0;
    std::array<glm::dvec3, 4> b;
    for (int i = 0; i < 4; ++i) b[i] = cp[curves[e][i]];
    if (options.mode == TessellationOptions::Mode::Uniform) {
      const double level = std::min<double>(options.uniformLevel, split ? half : maxLevel);
      out.lo[e] = level;
      out.hi[e] = split ? level : 0.0;
    } else if (!split) {
      out.lo[e] = curveLevel(b, viewProjection, viewport, options.pixelsPerSegment, half);
    } else {
      const glm::dvec3 b01 = 0.5 * (b[0] + b[1]), b12 = 0.5 * (b[1] + b[2]),
                       b23 = 0.5 * (b[2] + b[3]);
      const glm::dvec3 b012 = 0.5 * (b01 + b12), b123 = 0.5 * (b12 + b23);
      const glm::dvec3 m = 0.5 * (b012 + b123);
      out.lo[e] = curveLevel({b[0], b01, b012, m}, viewProjection, viewport,
                             options.pixelsPerSegment, half);
      out.hi[e] = curveLevel({m, b123, b23, b[3]}, viewProjection, viewport,
                             options.pixelsPerSegment, half);
    }
  }
  return out;
}

std::vector<uint32_t> tessVertexBounds(const PatchSet& patches, const glm::dmat4& viewProjection,
                                       const glm::dvec2& viewport,
                                       const TessellationOptions& requested) {
  const TessellationOptions options = effectiveOptions(requested, hasTransitionEdges(patches));
  std::vector<uint32_t> bounds(patches.patchCount());
  const bool adaptive = options.mode == TessellationOptions::Mode::Adaptive;
  for (uint32_t p = 0; p < patches.patchCount(); ++p) {
    PatchTessLevels levels = patchTessLevels(patches, p, viewProjection, viewport, options);
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
    if (patches.type(p) != PatchType::Bezier) continue;  // never back-patch culled when drawn
    const PatchTessLevels levels = patchTessLevels(patches, p, viewProjection, viewport, options);
    shapes[p] = bound::triangleShape({levels.lo, levels.hi}, slack);
  }
  return shapes;
}

}  // namespace osd_cull::frame
