#pragma once
/// \file tess_levels.h
/// \brief Tessellation options and a double-precision host mirror of the levels the patch
/// shaders compute (shaders/patch/tess_levels.glsl), used to plan draws and in tests.

#include "osd_cull/bound/drawn_triangles.h"
#include "osd_cull/patch/patch_set.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include <array>
#include <cstdint>

namespace osd_cull::frame {

/// \brief How patches are tessellated.
struct TessellationOptions {
  enum class Mode { Uniform, Adaptive };
  Mode mode = Mode::Uniform;
  /// Uniform: segments per patch edge (a transition edge gets this many per half). On a
  /// patch set with transition edges the level is clamped to maxLevel/2 everywhere, so that
  /// both halves of a transition edge fit and still match their finer neighbours
  /// (effectiveOptions()).
  uint32_t uniformLevel = 4;
  /// Adaptive: target length of one segment of an edge's screen-space control polygon.
  double pixelsPerSegment = 8.0;
  /// Largest level the device may generate (adaptive edges use at most half of it, so
  /// that a transition edge can hold two; as OpenSubdiv does).
  uint32_t maxLevel = 64;
};

/// \brief Levels of one patch: outer edges in gl_TessLevelOuter order (0: u=0, 1: v=0,
/// 2: u=1, 3: v=1), split into Lo and Hi halves (Hi is 0 except on transition edges).
struct PatchTessLevels {
  std::array<double, 4> lo{};
  std::array<double, 4> hi{};
  double outer(int e) const { return lo[e] + hi[e]; }
  double inner(int i) const {
    return i == 0 ? 0.5 * (outer(1) + outer(3)) : 0.5 * (outer(0) + outer(2));
  }
  /// \brief Vertices the tessellator emits for these levels (quads, equal spacing: levels
  /// round up; an inner level of 1 becomes 2 unless all levels are 1):
  /// (inner0 - 1)(inner1 - 1) + the four outer levels, 4 when all levels are 1. At most
  /// (m + 1)^2 for the largest level m. Equals the TES invocations lavapipe reports.
  uint32_t vertexCount() const;
};

/// \brief True when any patch has a transition edge (Far::PatchParam transition bits).
bool hasTransitionEdges(const PatchSet& patches);

/// \brief The options the shaders apply to a set: uniformLevel clamped to maxLevel/2 when
/// the set has transition edges. patchTessLevels() expects options made by this.
TessellationOptions effectiveOptions(const TessellationOptions& options, bool transitionEdges);

/// \brief The boundary-curve point indices of each edge (same table as the shaders).
std::array<std::array<uint32_t, 4>, 4> edgeCurveIndices(PatchType type);

/// \brief The levels the shaders compute for `patch`, in double precision, given the
/// effective options of its set.
PatchTessLevels patchTessLevels(const PatchSet& patches, uint32_t patch,
                                const glm::dmat4& viewProjection, const glm::dvec2& viewport,
                                const TessellationOptions& options);

/// \brief An upper bound of the tessellated vertices of each patch for this view,
/// allowing for fp32 rounding in the shader (one extra segment per adaptive level);
/// applies effectiveOptions() itself.
std::vector<uint32_t> tessVertexBounds(const PatchSet& patches, const glm::dmat4& viewProjection,
                                       const glm::dvec2& viewport,
                                       const TessellationOptions& options);

/// \brief The shape of the worst drawn triangle of every patch for this view
/// (bound::triangleShape of patchTessLevels()), as the double reference of the cull
/// kernel's drawn-triangle bound uses it: adaptive levels with a slack of one level (the
/// draw shader computes them in fp32); applies effectiveOptions() itself.
std::vector<bound::TriangleShape> drawnTriangleShapes(const PatchSet& patches,
                                                      const glm::dmat4& viewProjection,
                                                      const glm::dvec2& viewport,
                                                      const TessellationOptions& options);

}  // namespace osd_cull::frame
