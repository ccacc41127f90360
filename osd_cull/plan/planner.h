#pragma once
/// \file planner.h
/// \brief The effect plan (docs/algorithms/plan.md): per mesh instance and view, per frame,
/// which work runs — the cull stages (none, frustum, which back-patch method, occlusion),
/// two-pass or aggressive, the Hi-Z resolution, the control-point update (none, CPU, GPU)
/// and its bounds pass, the displacement kernel — decided from a device Calibration and
/// the cull rates measured on the mesh's recent frames.
///
/// Each frame the planner
///  1. tests the object's box against the view first (Sathe, last paragraph of the results: the
///  per-object pre-test):
///     a box outside the view is culled whole by the frustum stage; a box inside it makes
///     the frustum stage useless;
///  2. predicts every candidate stage choice with the cost model (cost_model.h: Zachmann's
///     T = t + (1 - P)·R, Niessner & Loop §6.3) at the rates learned so far (priors before
///     the first measurement) and takes the cheapest;
///  3. keeps the current choice unless the new one is predicted cheaper by a margin and the
///     current one has been held for some frames (hysteresis: no flipping every frame);
///  4. now and then runs a stage that is switched off for one frame (a re-probe), because a
///     rate can only be learned while its stage runs; each re-probe of a stage kind doubles
///     its interval until the inputs change (tessellation, image size, motion), so a steady
///     view converges on one choice.
/// observe() feeds the frame's measured per-stage cull counts back (a moving average) and
/// its measured time, split into the draw and the cull work where the frame measured both
/// (CullFrameStats::gpu): the model's draw cost and its cull cost are corrected apart, from
/// culled frames too. The unculled frame has its own scale, from frames drawn with no stage:
/// while the choice culls, an unculled check draws one such frame now and then
/// (PlannerOptions::unculledCheckFrames), keeping every cull configuration and its
/// visibility status, so that returning to culling does not draw everything (issue 18: an
/// unculled re-probe once threw the status away; the culled frames' draw time alone
/// predicted the displaced two-pass frame at 0.87 of its time and kept it where no culling
/// was 10% faster).
///
/// The planner never touches the device: applyPlan() turns a plan into the options that
/// the frame pipeline already takes (frame::CullFrameOptions, frame::CullSettings).

#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/frame/camera.h"
#include "osd_cull/frame/cull/cull_methods.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/patch/patch_set.h"
#include "osd_cull/plan/cost_model.h"

#include <cstdint>
#include <deque>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

namespace osd_cull::plan {

/// \brief Where an object's box lies against the view frustum (the per-object pre-test).
enum class BoxInView { Outside, Inside, Crossing };
const char* toString(BoxInView box);

/// \brief Sathe's pre-test: the eight corners of `objectBounds` moved by `model` into the
/// camera's clip space (in double). Outside: every corner is outside one plane (so every
/// control point is, and the frustum stage culls every patch). Inside: all corners are in
/// front of the eye and inside all planes (the frustum stage culls nothing). Else Crossing.
BoxInView boxInView(const frame::Bounds& objectBounds, const glm::dmat4& model,
                    const frame::Camera& camera);

/// \brief One mesh instance in one view at one frame: what the plan is made from.
struct PlanInput {
  std::string mesh;  ///< names for the printed plan
  std::string view;
  uint32_t bezier = 0;
  uint32_t gregory = 0;
  double tess = 4.0;
  frame::Bounds objectBounds;  ///< of the control points, object space
  glm::dmat4 model{1.0};
  frame::Camera camera;
  bool deforming = false;  ///< the cage can move (animated)
  bool cageMoved = false;  ///< ... and moved since the last frame
  bool displaced = false;  ///< a displacement map is bound to the mesh
  bound::BackPatchValidity backPatchValidity{false, "mesh validity not given"};
  /// Something can hide this mesh in this view: triangle occluders or other instances.
  bool occluders = false;
  /// The mesh can hide parts of itself (its surface is not convex): Hi-Z occlusion is a
  /// candidate even alone in the view. True when unknown (when unsure, offer it: a stage
  /// that does not pay is switched off by its measured rate); mayHideItself() decides it
  /// from the patches.
  bool selfOccluding = true;
  /// The frame applies this mesh's own back-patch accuracy and Hi-Z resolution and lookup
  /// (the mesh form). False in the scene form, whose one cull frame per view takes one
  /// CullSettings and one pyramid for every instance: then the accuracy stays the
  /// drawn-triangle bound and the pyramid the paper's (half resolution, paper lookup).
  bool ownAccuracy = true;
};

/// \brief Whether a mesh can hide parts of itself in some view from outside, i.e. whether
/// its surface may be non-convex. Conservative in the planner's sense, "when unsure, yes":
/// false only when every sampled limit point (the corners of every Bézier patch, which lie
/// on the limit surface) lies on one side of the tangent plane at every Bézier patch corner
/// (the plane through the corner and its two edge control points), which a convex surface
/// satisfies. A mesh of more than `maxWork` point-plane tests, or without Bézier patches,
/// or with a degenerate corner everywhere, gets true. Several disjoint convex objects in
/// one set fail the test (they can hide each other): true.
bool mayHideItself(const PatchSet& patches, uint64_t maxWork = 100'000'000);

/// \brief The uniform level that costs what `tessellation` draws of `patches` from `camera`
/// (object → world by `model`): sqrt of the mean tessellated vertex count over the patches
/// (PatchTessLevels::vertexCount, (L + 1)^2 at uniform level L) less one, from at most
/// `samples` patches spread over the set. A uniform tessellation returns its level; the
/// planner's cost model, calibrated at uniform levels, plans an adaptive one with this.
double equivalentUniformLevel(const PatchSet& patches, const frame::Camera& camera,
                              const glm::dmat4& model,
                              const frame::TessellationOptions& tessellation,
                              uint32_t samples = 2048);

/// \brief The effects of a plan, in print order: the three cull stages, the back-patch
/// test's accuracy, the passes, the Hi-Z pyramid, the control-point update, the bounds pass
/// and the displacement kernel. Each has its own function in the planner that produces its
/// decision and the sentence that gives its reason, so that the two cannot disagree.
enum class EffectKind {
  Frustum,
  BackPatch,
  Accuracy,
  Occlusion,
  Passes,
  HiZ,
  Update,
  Bounds,
  Displacement
};

/// \brief "frustum", "back-patch", "accuracy", "occlusion", "passes", "hi-z", "update",
/// "bounds", "displacement".
const char* toString(EffectKind kind);

/// \brief One effect of a plan: on or off, the choice made (a method, "cpu"), why, and
/// the predicted change of the frame time it makes (negative: it saves time).
struct Effect {
  bool on = false;
  std::string choice;
  std::string reason;
  double deltaMs = 0.0;
};

/// \brief The plan of one mesh instance in one view for one frame.
struct Plan {
  std::string mesh, view;
  uint64_t frame = 0;
  BoxInView box = BoxInView::Crossing;
  StageChoice stages;
  Effect frustum, backPatch, accuracy, occlusion, passes, hiz, update, bounds, displacement;
  bool probe = false;  ///< a re-probe frame (a switched-off stage runs once)
  /// An unculled check (PlannerOptions::unculledCheckFrames, also a probe): this frame draws
  /// with no stage at all, so that the frame without culling is measured, not only predicted.
  bool unculledCheck = false;
  /// Back-patch variants (method and accuracy, with this frame's frustum stage) to run in a
  /// counting-only pass this frame: their kernels cull nothing that is drawn and the
  /// visibility status is untouched; their culls go to Planner::observeCount(). Set on a
  /// key's first frame for every offered variant but the frame's own, so that the choice
  /// after exploring compares measured rates, not one measured rate and priors (issue 18:
  /// BigGuy at tess 4 kept NCONE, the one method measured, where the tangent plane culled
  /// more).
  std::vector<StageChoice> countOnly;
  CullRates rates;  ///< the rates the prediction used
  /// Measured / predicted time of the draw work (patch draws, submission, point update) and
  /// of the cull work (kernels, pyramid, status) learned on this key's recent frames (1
  /// before the first): the calibration's costs scaled to what this mesh costs on this
  /// machine now.
  double drawScale = 1.0, cullScale = 1.0;
  CostCase cost;                 ///< what the prediction was made for (observe re-predicts)
  Prediction predicted;          ///< this plan, scaled
  Prediction predictedUnculled;  ///< no stage at all, scaled
  /// \brief Whether anything is culled (else the mesh is drawn by the plain renderer).
  bool culls() const { return stages.any(); }
  /// \brief The effects with their kinds, in print order.
  std::vector<std::pair<EffectKind, const Effect*>> effects() const;
  /// \brief The effect of `kind`.
  const Effect& effect(EffectKind kind) const;
};

/// \brief Tuning of the planner.
struct PlannerOptions {
  /// Hysteresis: a new stage choice replaces the current one only when predicted at least
  /// this share cheaper ...
  double margin = 0.05;
  /// ... and the current one has run for at least this many frames.
  uint32_t holdFrames = 8;
  /// A stage switched off runs for one frame after this many frames, to re-measure its
  /// rate (0: never). Each re-probe of a kind doubles its interval, up to
  /// maxReprobeFrames, until the inputs change (PlanInput: tessellation, image size,
  /// deforming, displaced, occluders): a steady view stops probing.
  uint32_t reprobeFrames = 48;
  uint32_t maxReprobeFrames = 768;
  /// A choice changed this many times within the last 64 frames raises the hysteresis
  /// margin by `margin` each (at most 0.5): two choices predicted alike cannot alternate.
  uint32_t oscillationWindow = 64;
  /// The back-patch methods the plan may choose (empty: every calibrated one); e.g. the
  /// user's --backpatch-method given with --plan auto.
  std::vector<std::string> backPatchMethods;
  /// A stage kind (frustum, back-patch, occlusion) never measured for a key, whose rate is
  /// only a prior (a figure of other meshes), runs for one frame after this many frames
  /// instead (0: like the others). Without it a stage whose prior lies below its break-even
  /// waited reprobeFrames before its first measurement (the displaced character of
  /// docs/results/plan.md, "Scenes": occlusion off for the first 48 frames, then on).
  uint32_t firstProbeFrames = 2;
  /// The first frames of a key run every stage kind it offers at once (frustum where the
  /// box is not inside the view, the back-patch method and occlusion kernel predicted
  /// cheapest): each stage's rate is measured from the start (a patch counts for the first
  /// stage that culls it, as the model counts it), so the choice of the frames after is made
  /// on measured rates, not priors, and needs no probe soon after (0: start from the
  /// priors' choice). Two frames: a new two-pass frame's first one cannot measure occlusion.
  uint32_t exploreFrames = 2;
  /// While the current choice culls, one frame is drawn with no stage at all (an unculled
  /// check: Plan::unculledCheck) right after exploring and again after this many frames,
  /// each check doubling the interval up to maxReprobeFrames until the inputs change (0:
  /// never). It teaches the unculled frame's own time scale: the culled frames' draw time
  /// predicts it only as well as the model's draw cost carries from the patches a culled
  /// frame draws to all of them (issue 18: the displaced BigGuy's two-pass frame at tess 2
  /// and 4 was predicted at 0.87 of its time and kept where no culling was 10% faster).
  /// The frame keeps every cull configuration and its visibility status (MeshSession's
  /// cache), so the frame after it culls from a status one frame old.
  uint32_t unculledCheckFrames = 8;
  /// Unculled checks right after exploring, one after the other (0: the first check comes
  /// unculledCheckFrames after the inputs changed). Off by default: on the held-out
  /// characters (docs/results/plan.md, session 13) the two checks right after exploring
  /// were a third of the first eight frames, drawn unculled where culling saved 45% (tess
  /// 16: planned 1.47 of all culling); the culled frames' own draw time predicts the
  /// unculled frame until the first periodic check measures it.
  uint32_t unculledFirstChecks = 0;
  /// The checks run only while the choice is predicted to save less than this share of the
  /// unculled frame: the predictions are within about 15% of the measured frames
  /// (docs/results/plan.md), so a larger saving is not in doubt and is not paid for with
  /// unculled frames (the held-out characters at tess 4 and 16 save 25-45%).
  double unculledCheckBelow = 0.15;
  /// Plan::countOnly on a key's first frame (false: an unmeasured back-patch variant borrows
  /// its measured sibling's rate, Planner::rate).
  bool countingProbes = true;
  /// Weight of a new measurement in the moving average of a rate.
  double learnWeight = 0.5;
  /// Plan::drawScale and cullScale are the median of this many last measured frames.
  size_t scaleWindow = 5;
  /// Aggressive culling (§3.1) shows newly visible patches one frame late: only when
  /// allowed.
  bool allowAggressive = false;
  /// Culled patches are drawn with tessellation factor 0 (CullDrawMode::TessFactorZero).
  bool tessFactorZero = false;
  /// Prior cull rates (share of all patches) before a stage's first measurement: per
  /// back-patch method (tested on the drawn triangles; the held-out character at
  /// tess 8: TCONE 12.7%, tangent plane 18.7%), occlusion, and the frustum stage of a box
  /// that crosses the view.
  std::map<std::string, double> priorRates = {
      {"frustum", 0.3},
      {"tcone", 0.12},
      {"ncone", 0.15},
      {"tangent-plane", 0.18},
      {"tangent-plane-16", 0.18},
      {"hiz", 0.10},
      // The displaced kernels: the Hi-Z prior times the share of the undisplaced Hi-Z rate
      // each kept on BigGuy level 1 (docs/results/displacement.md, Table 1: 15.8% ... 26.2%
      // against 34.7%).
      {"full-oobb", 0.046},
      {"acon-oobb", 0.058},
      {"con-oobb", 0.059},
      {"full-caf", 0.061},
      {"acon-caf", 0.074},
      {"con-caf", 0.076}};
  /// The back-patch accuracy (Accuracy): "auto" chooses the drawn-triangle bound or the
  /// listed triangles by predicted cost (both conservative for the drawn triangles);
  /// "bound", "listed" or "surface" force one. Surface-exact (the papers' test, which can
  /// lose silhouette pixels of the drawn chord triangles) is never chosen unless asked for.
  std::string accuracy = "auto";
  /// Prior rate of a back-patch method at the listed-triangle and surface-exact accuracies,
  /// as a multiple of its bound prior: docs/results/accuracy-vs-time.md, BigGuy at 1280x720
  /// tess 4 to 16, listed/bound 1.5 to 2.2 (tcone 30.5% / 13.7%, tangent plane 36.4% /
  /// 19.1%), surface/bound 2.1 to 2.5 (tcone 34.3%, ncone 39.4% / 17.7%).
  double listedRateFactor = 1.9;
  double surfaceRateFactor = 2.2;
  /// Prior occlusion rate with the tight Hi-Z lookup, and with level 0 at full resolution,
  /// as a multiple of the paper's (half, paper lookup): docs/results/occlusion.md, the tight
  /// lookup culls 1.07 to 1.18 times as much (default scene 52.3% / 49.1%, BigGuy level 0
  /// 28.3% / 23.9%); full resolution is not measured there: taken as the same one-level-
  /// finer gain. Learned per variant (RateKey) as soon as one runs.
  double tightRateFactor = 1.13;
  double fullRateFactor = 1.13;
  /// The displaced kernel for a displaced mesh when the calibration measured none of the
  /// six (Niessner & Loop Table 1: CoN with the camera-aligned frustum culls most); with
  /// measured ones the planner takes the cheapest predicted.
  std::string displacedKernel = "con-caf";
};

/// \brief The identity of a learned cull rate: a stage and, for a back-patch stage, its
/// method and accuracy; for an occlusion stage, its kernel and pyramid (level 0 at full
/// resolution, the tight lookup). Each variant culls differently, so each is learned apart;
/// an unmeasured one borrows its measured sibling's rate (Planner::rate). Ordered, so that it
/// keys the planner's maps.
struct RateKey {
  frame::CullStage stage = frame::CullStage::Frustum;
  std::string method;  ///< back-patch method or occlusion kernel; empty for the frustum
  Accuracy accuracy = Accuracy::Bound;     ///< back-patch
  bool hizFull = false, hizTight = false;  ///< occlusion

  static RateKey frustum();
  static RateKey backPatch(std::string method, Accuracy accuracy = Accuracy::Bound);
  /// \brief The occlusion stage of `stages` with its pyramid.
  static RateKey occlusion(const StageChoice& stages);
  static RateKey occlusion(std::string kernel, bool hizFull = false, bool hizTight = false);
  /// \brief The key printed as `name` ("frustum", "tcone", "tcone/listed", "hiz/full/tight").
  /// \throws osd_cull::Error naming the part it does not know.
  static RateKey parse(const std::string& name);
  /// \brief "frustum", the method's name for the bound ("tcone"), "tcone/listed",
  /// "tcone/surface"; the kernel's name on the paper's pyramid ("hiz"), "hiz/full",
  /// "hiz/tight", "hiz/full/tight".
  std::string name() const;
  /// \brief The same method at the drawn-triangle bound, the same kernel on the paper's
  /// pyramid: the key of its plain prior.
  RateKey plain() const;
  auto operator<=>(const RateKey&) const = default;
};

/// \brief What a frame that ran a plan measured.
struct Observation {
  /// Patches culled by each stage (a patch counts for the first that culls it; as
  /// CullFrameStats counts them) of `total`.
  uint32_t culledFrustum = 0, culledBackPatch = 0, culledOcclusion = 0, total = 0;
  /// The frame's time without point update and bounds pass (0: not timed).
  double ms = 0.0;
  /// Of `ms`, the cull work: the kernels, the pyramid build and the status update
  /// (CullFrameStats::gpu.pyramid + gpu.cull). NaN where the frame did not time it apart
  /// (one-pass culling): then `ms` corrects the two scales together.
  double cullMs = std::numeric_limits<double>::quiet_NaN();
  /// Patches the frame drew, both passes (CullFrameStats::drawnPass1 + drawnPass2); unset
  /// where not counted. The draw scale is learned against the drawn count: while the
  /// visibility status lags the view, pass 1 draws patches the occlusion test then culls.
  std::optional<uint32_t> drawn;
};

/// \brief The planner. One per program; it keeps a state per key (instance and view).
class Planner {
 public:
  explicit Planner(Calibration calibration, PlannerOptions options = {});

  /// \brief The plan of `input` for frame `frame` under `key` (e.g. "view/instance").
  /// Frames of one key must come in increasing order.
  /// \throws osd_cull::Error when the calibration lacks a stage's cost.
  Plan plan(const std::string& key, const PlanInput& input, uint64_t frame);

  /// \brief Learns from a frame that ran `plan` (see Observation): the rates, and from the
  /// times Plan::drawScale and cullScale (the load of a shared machine, caches, the mesh's
  /// screen coverage: what the calibration did not see).
  void observe(const std::string& key, const Plan& plan, const Observation& frame);
  /// \brief observe() with counts and the frame's wall time only (no split).
  /// \brief Learns the back-patch rate of `stages` (one of Plan::countOnly) from a
  /// counting-only pass: `culled` of `total` patches culled by its back-patch stage.
  void observeCount(const std::string& key, const StageChoice& stages, uint32_t culled,
                    uint32_t total);
  void observe(const std::string& key, const Plan& plan, uint32_t culledFrustum,
               uint32_t culledBackPatch, uint32_t culledOcclusion, uint32_t total,
               double measuredMs = 0.0);

  /// \brief The learned (or prior) rate of `stage` for `key`.
  double rate(const std::string& key, const RateKey& stage) const;
  /// \brief rate() of the stage printed as `stage` (RateKey::parse).
  double rate(const std::string& key, const std::string& stage) const;
  const Calibration& calibration() const { return calibration_; }
  const PlannerOptions& options() const { return options_; }

 private:
  struct State {
    std::optional<StageChoice> current;
    uint64_t since = 0;  // frame the current choice started
    std::map<RateKey, double> rates;
    std::map<frame::CullStage, uint64_t> lastRun;        // stage → last frame it ran
    std::map<frame::CullStage, uint32_t> probeInterval;  // stage → frames between probes
    std::set<frame::CullStage> measured;                 // stages observed at least once
    uint64_t lastFrame = 0;
    std::string inputs;                  // inputsSignature() of the last plan
    std::deque<uint64_t> switches;       // frames the choice changed, the last window
    std::optional<StageChoice> hold;     // an occlusion probe's second frame runs this
    std::optional<uint64_t> firstFrame;  // the key's first planned frame
    bool explored = false;               // exploring until the last frame
    std::optional<RateKey> lastBackPatchKey, lastOcclusionKey;  // last measured variant of each
    // Plan::drawScale and cullScale: the calibration's draw and cull costs can be off by
    // different factors for a given mesh (its screen coverage, its patch shapes); a frame
    // that times its cull work apart tells them apart. Until one is measured it takes the
    // other's.
    double drawScale = 1.0, cullScale = 1.0;
    bool drawMeasured = false, cullMeasured = false;
    std::deque<double> drawRatios, cullRatios;  // the last measured / model ratios
    std::vector<StageChoice> observed;          // the stage choices observed at least once
    // The unculled frame's scale, learned from frames drawn with no stage (unculled checks,
    // a choice of none); the culled choices' draw scale only from culled frames. Until one is
    // measured it takes the other's.
    double unculledScale = 1.0;
    bool unculledMeasured = false;
    std::deque<double> unculledRatios;
    uint64_t lastUnculled = 0;      // the last frame drawn with no stage
    uint32_t unculledInterval = 0;  // frames between unculled checks (0: not started)
    double drawScaleNow() const {
      if (drawMeasured) return drawScale;
      if (unculledMeasured) return unculledScale;
      return cullMeasured ? cullScale : drawScale;
    }
    double unculledScaleNow() const { return unculledMeasured ? unculledScale : drawScaleNow(); }
    // The draw scale of choice `c`.
    double drawScaleFor(const StageChoice& c) const {
      return c.any() ? drawScaleNow() : unculledScaleNow();
    }
    double cullScaleNow() const { return cullMeasured || !drawMeasured ? cullScale : drawScale; }
  };
  /// The frame time of choice `c` predicted for `input`, in this key's measured time.
  double predictedMs(const State& state, const PlanInput& input, const StageChoice& c,
                     BoxInView box) const;
  CostCase costCase(const PlanInput& input, const StageChoice& stages) const;
  bool offersOcclusion(const PlanInput& input) const;
  std::string occlusionKernel(const PlanInput& input) const;
  std::vector<std::string> occlusionKernels(const PlanInput& input) const;
  std::string bestOcclusionKernel(const PlanInput& input, const State& state,
                                  const StageChoice& stages, BoxInView box) const;
  std::vector<StageChoice> candidates(const PlanInput& input) const;
  std::string displacedBoundsKernel(const PlanInput& input, const StageChoice& stages) const;
  std::vector<Accuracy> accuracies(const PlanInput& input, const std::string& method) const;
  CullRates ratesFor(const State& state, const StageChoice& stages, BoxInView box) const;
  bool uncertainSaving(double culledMs, double unculledMs) const;
  uint32_t doubledInterval(uint32_t interval, uint32_t first) const;
  bool choose(State& state, const PlanInput& input, const std::vector<StageChoice>& all, Plan& plan,
              uint64_t frame) const;
  void reprobe(State& state, const PlanInput& input, const std::vector<StageChoice>& all,
               Plan& plan, uint64_t frame, bool exploring) const;
  double stageRate(const State& state, const RateKey& stage) const;
  double priorRate(const RateKey& stage) const;
  /// One function per effect (planner.cpp): each returns the effect's decision with its
  /// reason.
  struct Explaining;
  void explain(Plan& plan, const PlanInput& input, const State& state) const;

  Calibration calibration_;
  PlannerOptions options_;
  std::map<std::string, State> states_;
};

/// \brief `base` with the plan's stages, back-patch accuracy (CullSettings::drawnTriangles,
/// drawnEnumerate), passes, Hi-Z resolution and lookup, and displaced kernel.
/// The back-patch validity and the displacement map of `base` are kept (a displaced mesh's
/// map stays bound only when the plan says displacement is on).
frame::CullFrameOptions applyPlan(const Plan& plan, frame::CullFrameOptions base);

/// \brief The plans as a table: mesh, view, each effect on/off with its choice, reason
/// and predicted ms, and the predicted frame against no culling.
std::string planTable(std::span<const Plan> plans);

/// \brief One line per effect that differs between `before` and `after` ("" when none).
std::string planChange(const Plan& before, const Plan& after);

}  // namespace osd_cull::plan
