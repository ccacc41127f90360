#pragma once
/// \file cost_model.h
/// \brief Predicted frame time of one mesh (instance) in one view for a choice of cull
/// stages, from a device Calibration and the stages' cull rates.
///
/// Zachmann's cost model of a culling test (zachmann-culling-lecture, clustered back-face
/// culling): T = t + (1 - P)·R, with t the test's cost, P the probability that it culls and
/// R the cost of rendering what it would cull. Per patch, with the terms of Niessner & Loop
/// §6.3: t = CT (the stages' kernel cost), R = RT(tf) — for a patch that faces away or lies
/// off screen the cheaper RT of a patch the rasterizer discards unshaded, since back faces
/// are culled in the draws either way — and a culled patch still costs RT0
/// when it is drawn with tessellation factor 0 (their §5 variant; our default compact draw
/// lists do not draw it: RT0 = 0). Their break-even cull rate follows from T = R:
///   x = (RT0 + CT) / (RT - RT0).
/// Fixed costs are added once per frame: the submission, the cull dispatch, and with
/// occlusion the Hi-Z build (against the pyramid's pixel count) and the second pass.

#include "osd_cull/plan/calibration.h"

#include <cstdint>
#include <string>

namespace osd_cull::plan {

/// \brief Share of all patches that each stage culls (as CullFrameStats counts them: a
/// patch counts for the first stage that culls it), each in [0, 1].
struct CullRates {
  double frustum = 0.0;
  double backPatch = 0.0;
  double occlusion = 0.0;
  /// With the listed-triangle accuracy: the share of patches the listed test runs on (those
  /// the surface test culls and the bound keeps), which its calibrated cost is per.
  double listedRuns = 0.0;
};

/// \brief The accuracy of the back-patch test (docs/algorithms/drawn-triangles.md):
/// conservative for the drawn chord triangles by the worst-case bound (Bound, the default and
/// cheapest), by testing the listed triangles the tessellator draws where the bound keeps a
/// patch (Listed, CullSettings::drawnEnumerate: culls about twice as much, at a per-patch
/// cost that grows with the level), or the papers' surface-exact test (Surface, not
/// conservative for the drawn triangles: it can lose silhouette pixels).
enum class Accuracy { Bound, Listed, Surface };
/// \brief "bound", "listed", "surface".
const char* toString(Accuracy accuracy);

/// \brief Which cull stages run for a mesh in a view, and how.
struct StageChoice {
  bool frustum = false;
  std::string backPatch;    ///< a back-patch method name; empty: none
  std::string occlusion;    ///< "hiz" or a displaced kernel ("con-caf", ...); empty: none
  bool hizFull = false;     ///< Hi-Z level 0 at full resolution (paper: half)
  bool hizTight = false;    ///< the tight Hi-Z lookup (paper: HiZLookup::Paper)
  bool aggressive = false;  ///< one pass, newly visible patches a frame late (§3.1)
  Accuracy accuracy = Accuracy::Bound;  ///< of the back-patch test
  /// \brief True when any stage runs (else the mesh is drawn by the plain renderer).
  bool any() const { return frustum || !backPatch.empty() || !occlusion.empty(); }
  bool operator==(const StageChoice&) const = default;
  /// \brief "none", "frustum", "frustum + tcone + hiz (two-pass, half)", "tcone/listed".
  std::string describe() const;
};

/// \brief Everything but the stages that the cost of a frame depends on.
struct CostCase {
  uint32_t bezier = 0;          ///< Bézier patches of the mesh
  uint32_t gregory = 0;         ///< Gregory patches
  double tess = 1.0;            ///< uniform tessellation level
  uint64_t pixels = 0;          ///< the view's image size (width × height)
  bool tessFactorZero = false;  ///< culled patches drawn with factor 0 (then RT0 counts)
  bool pointUpdate = false;     ///< the cage moved: control points are recomputed
  bool gpuPointUpdate = false;  ///< ... in Vulkan compute (else on the CPU)
  bool boundsPass = false;      ///< the bounds pass of the back-patch method runs
  std::string boundsMethod;     ///< ... of this method (Calibration::boundsMs)
  bool displaced = false;       ///< drawn displaced: RT(tf) times displacedDrawFactorAt
  uint32_t patches() const { return bezier + gregory; }
};

/// \brief A predicted frame, in ms.
struct Prediction {
  /// N·RT less what the culled patches would have cost (RT of a back-facing patch for
  /// the frustum and back-patch stages, RT for occlusion), plus P·N·RT0.
  double drawMs = 0.0;
  double cullMs = 0.0;    ///< N·CT + the dispatch
  double hizMs = 0.0;     ///< the Hi-Z build and the second pass's fixed cost
  double updateMs = 0.0;  ///< point update and bounds pass
  double fixedMs = 0.0;   ///< the submission
  double culled = 0.0;    ///< P, the share of patches not drawn
  double totalMs() const { return drawMs + cullMs + hizMs + updateMs + fixedMs; }
};

/// \brief The pixels of the Hi-Z pyramid's level 0 for an image of `pixels`.
uint64_t hizPixels(uint64_t pixels, bool fullResolution);

/// \brief RT(tf) averaged over the mesh's patch types (Gregory patches cost
/// Calibration::gregoryDrawFactor times a Bézier patch); a displaced mesh's times
/// Calibration::displacedDrawFactorAt(tf).
double drawMsPerPatch(const Calibration& calibration, const CostCase& c);

/// \brief RT of a patch whose triangles all face away (Calibration::backDrawMs), averaged
/// over the patch types: what a patch culled by the frustum or back-patch stage saves.
double backDrawMsPerPatch(const Calibration& calibration, const CostCase& c);

/// \brief CT of `stages` per patch at uniform level `tess` (the sum of the stages'
/// calibrated costs; the back-patch stage's at its accuracy, the listed test's at `tess`
/// times the share of patches it runs on, `rates.listedRuns`).
double cullMsPerPatch(const Calibration& calibration, const StageChoice& stages, double tess,
                      const CullRates& rates);

/// \brief T = t + (1 - P)·R (+ P·RT0) plus the fixed costs, for `stages` culling at
/// `rates` (only the rates of stages that run count).
Prediction predict(const Calibration& calibration, const CostCase& c, const StageChoice& stages,
                   const CullRates& rates);

/// \brief Niessner & Loop §6.3: the cull rate above which culling pays,
/// x = (RT0 + CT) / (RT - RT0); +infinity when RT <= RT0.
double breakEvenRate(double rt, double rt0, double ct);

}  // namespace osd_cull::plan
