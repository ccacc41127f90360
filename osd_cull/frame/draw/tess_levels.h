#pragma once
/// \file tess_levels.h
/// \brief Tessellation options and a double-precision host mirror of the levels the patch
/// shaders compute (shaders/patch/tess_levels.glsl), used to plan draws and in tests.

#include "osd_cull/bound/displaced_map.h"
#include "osd_cull/bound/drawn_triangles.h"
#include "osd_cull/patch/patch_set.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace osd_cull::frame {

/// \brief How adaptive levels of a displaced patch set account for the displacement
/// (docs/algorithms/displacement.md, "Tessellation"; uniform levels never do).
enum class DisplacedTessellation {
  /// Each edge adds the screen length of the displacement's variation along it
  /// (EdgeDisplacement): computed from what both patches sharing the edge see alike, so
  /// shared edges get the same level (crack-free wherever the map is continuous).
  EdgeVariation,
  /// The undisplaced edge's level (the cost baseline).
  Ignore,
  /// Every edge of a patch adds the largest variation of its four edges: neighbours
  /// disagree, so shared edges get different levels and the surface cracks. Not for
  /// drawing: the counter-example the crack tests and `render --displaced-tess` measure.
  PerPatch,
};

/// \brief "edge", "none", "per-patch" (the `--displaced-tess` names).
const char* toString(DisplacedTessellation mode);

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
  /// Adaptive levels of displaced sets (ignored for undisplaced ones).
  DisplacedTessellation displaced = DisplacedTessellation::EdgeVariation;
};

/// \brief The displacement's variation along each edge of a patch, in object units
/// (DisplacementMap::variationAlong over the edge's texture-coordinate segment), for the
/// whole edge and its halves (the Lo and Hi halves of a transition edge), edges in
/// gl_TessLevelOuter order. A function of the edge's two texture coordinates (rounded to
/// float, as the draw holds them) and the map only: the same on both sides of an edge
/// wherever the texture coordinates are continuous across it.
struct EdgeDisplacement {
  std::array<float, 4> whole{};
  std::array<float, 4> firstHalf{};
  std::array<float, 4> secondHalf{};
};

/// \brief EdgeDisplacement of every patch; `uvCorners`: 4 per patch, corners (0,0), (1,0),
/// (1,1), (0,1) (PatchExtraction::uvCorners).
/// \throws osd_cull::Error when the corner count is not 4 * patchCount.
std::vector<EdgeDisplacement> edgeDisplacements(const bound::DisplacementMap& map,
                                                std::span<const glm::dvec2> uvCorners,
                                                uint32_t patchCount);

/// \brief The displacement length each edge (Lo, Hi halves) adds under `mode`: none for
/// Ignore, the edge's own for EdgeVariation, the patch's largest for PerPatch.
/// `split[e]`: edge e is a transition edge (the halves are used).
void edgeDisplacementTerms(const EdgeDisplacement& d, DisplacedTessellation mode,
                           const std::array<bool, 4>& split, std::array<double, 4>& lo,
                           std::array<double, 4>& hi);

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
/// effective options of its set; `displacement`: the patch's EdgeDisplacement when the set
/// is displaced (adaptive levels add its screen length, options.displaced).
PatchTessLevels patchTessLevels(const PatchSet& patches, uint32_t patch,
                                const glm::dmat4& viewProjection, const glm::dvec2& viewport,
                                const TessellationOptions& options,
                                const EdgeDisplacement* displacement = nullptr);

/// \brief An upper bound of the tessellated vertices of each patch for this view,
/// allowing for fp32 rounding in the shader (one extra segment per adaptive level);
/// applies effectiveOptions() itself. `displacement`: one per patch for a displaced set.
std::vector<uint32_t> tessVertexBounds(const PatchSet& patches, const glm::dmat4& viewProjection,
                                       const glm::dvec2& viewport,
                                       const TessellationOptions& options,
                                       std::span<const EdgeDisplacement> displacement = {});

/// \brief The shape of the worst drawn triangle of every patch for this view
/// (bound::triangleShape of patchTessLevels()), as the double reference of the cull
/// kernel's drawn-triangle bound uses it: adaptive levels with a slack of one level (the
/// draw shader computes them in fp32); applies effectiveOptions() itself.
std::vector<bound::TriangleShape> drawnTriangleShapes(const PatchSet& patches,
                                                      const glm::dmat4& viewProjection,
                                                      const glm::dvec2& viewport,
                                                      const TessellationOptions& options);

/// \brief drawnTriangleShapes() for levels known exactly (one per patch: the levels pass's,
/// readTessLevels()): no slack, so the listed test can run on them too.
std::vector<bound::TriangleShape> drawnTriangleShapes(std::span<const PatchTessLevels> levels);

}  // namespace osd_cull::frame
