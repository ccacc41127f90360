#include "osd_cull/plan/planner.h"

#include "osd_cull/bound/frustum.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/bounds_pass.h"
#include "osd_cull/frame/cull/cull_methods.h"
#include "osd_cull/frame/draw/tess_levels.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace osd_cull::plan {
namespace {

using frame::CullStage;

// The draw work (patch draws, submission, point update) times `draw`, the cull work
// (kernels, pyramid, status) times `cull`.
Prediction scaled(Prediction p, double draw, double cull) {
  p.drawMs *= draw;
  p.fixedMs *= draw;
  p.updateMs *= draw;
  p.cullMs *= cull;
  p.hizMs *= cull;
  return p;
}

// What the plan's choice depends on besides the view: a change starts the re-probes over.
// The level in steps of a quarter octave (an adaptive level drifts with the camera).
std::string inputsSignature(const PlanInput& in) {
  const long level = std::lround(4.0 * std::log2(std::max(in.tess, 1.0)));
  return std::to_string(level) + "/" + std::to_string(in.camera.width) + "x" +
         std::to_string(in.camera.height) + "/" + std::to_string(in.deforming) +
         std::to_string(in.displaced) + std::to_string(in.occluders) +
         std::to_string(in.backPatchValidity.enabled);
}

// A back-patch method whose per-patch cull data the bounds pass recomputes from moved
// points (TCONE, NCONE: the Bézier cones; the tangent-plane methods: the Gregory TCONE and
// the drawn-triangle bound's G, H; frame/cull/bounds_pass.h): it can run on a deforming
// mesh, with the bounds pass charged to it.
bool hasBoundsPass(const std::string& method) {
  return frame::BoundsPass::hasCullData(frame::cullMethod(method).reference);
}

// "full", "acon" or "con": the displaced extension of displaced kernel `kernel`.
std::string displacedExtensionOf(const std::string& kernel) {
  for (const frame::CullMethod& m : frame::displacedCullMethods())
    if (m.name == kernel) return bound::toString(m.displaced->extension);
  throw Error("planner: '" + kernel + "' is not a displaced kernel");
}

// A measured rate into the moving average of `stage` (the first measurement replaces the
// prior).
void learnRate(std::map<RateKey, double>& rates, const RateKey& stage, double rate, double weight) {
  const auto it = rates.find(stage);
  rates[stage] = it == rates.end() ? rate : (1.0 - weight) * it->second + weight * rate;
}

std::string percent(double rate) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f%%", 100.0 * rate);
  return text;
}

std::string ms(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f ms", v);
  return text;
}

/// The median of `values` (the mean of the two middle ones for an even count).
double median(const std::deque<double>& values) {
  std::vector<double> v(values.begin(), values.end());
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

const char* toString(BoxInView box) {
  switch (box) {
    case BoxInView::Outside:
      return "outside";
    case BoxInView::Inside:
      return "inside";
    case BoxInView::Crossing:
      return "crossing";
  }
  return "?";
}

BoxInView boxInView(const frame::Bounds& b, const glm::dmat4& model, const frame::Camera& camera) {
  std::vector<glm::dvec3> corners;
  for (int i = 0; i < 8; ++i)
    corners.push_back({i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z});
  const bound::ClipBounds clip = bound::clipBounds(corners, camera.viewProjection() * model);
  if (!clip.finite) return BoxInView::Crossing;  // keep it: no pre-test verdict
  if (clip.outsideAll != 0) return BoxInView::Outside;
  if (clip.outsideAny == 0 && !clip.behindEye) return BoxInView::Inside;
  return BoxInView::Crossing;
}

bool mayHideItself(const PatchSet& patches, uint64_t maxWork) {
  // The sampled limit points: the four corners of every patch (Bézier: points 0, 3, 12, 15;
  // Gregory: its corner points come first in each corner's group of five).
  std::vector<glm::dvec3> corners;
  for (uint32_t p = 0; p < patches.patchCount(); ++p) {
    const auto cp = patches.controlPoints(p);
    if (patches.type(p) == PatchType::Bezier)
      corners.insert(corners.end(), {cp[0], cp[3], cp[12], cp[15]});
    else
      for (uint32_t k = 0; k < 4; ++k) corners.push_back(cp[5 * k]);
  }
  // The tangent planes at the Bézier corners: corner, and its neighbours along u and v.
  static constexpr int kCorner[4][3] = {{0, 1, 4}, {3, 7, 2}, {15, 14, 11}, {12, 8, 13}};
  const uint64_t planes = 4ull * patches.bezierCount;
  if (planes == 0 || planes * corners.size() > maxWork) return true;  // unsure: offer it
  const frame::Bounds box = frame::boundsOf(patches.points);
  const double tolerance = 1e-9 * std::max(box.radius(), 1e-300);
  bool anyPlane = false;
  for (uint32_t p = 0; p < patches.bezierCount; ++p) {
    const auto cp = patches.controlPoints(p);
    for (const auto& [c, u, v] : kCorner) {
      const glm::dvec3 n = glm::cross(cp[u] - cp[c], cp[v] - cp[c]);
      const double length = glm::length(n);
      if (!(length > 0.0) || !std::isfinite(length)) continue;  // degenerate corner
      anyPlane = true;
      const glm::dvec3 unit = n / length;
      bool above = false, below = false;
      for (const glm::dvec3& q : corners) {
        const double d = glm::dot(unit, q - cp[c]);
        above |= d > tolerance;
        below |= d < -tolerance;
        if (above && below) return true;  // points on both sides: not convex
      }
    }
  }
  return !anyPlane;
}

double equivalentUniformLevel(const PatchSet& patches, const frame::Camera& camera,
                              const glm::dmat4& model,
                              const frame::TessellationOptions& tessellation, uint32_t samples) {
  const frame::TessellationOptions o =
      frame::effectiveOptions(tessellation, frame::hasTransitionEdges(patches));
  if (o.mode != frame::TessellationOptions::Mode::Adaptive) return o.uniformLevel;
  const uint32_t n = patches.patchCount();
  if (n == 0) return 1.0;
  const uint32_t step = std::max(1u, n / std::max(1u, samples));
  const glm::dmat4 viewProjection = camera.viewProjection() * model;
  const glm::dvec2 viewport(camera.width, camera.height);
  double vertices = 0.0;
  uint32_t count = 0;
  for (uint32_t p = 0; p < n; p += step, ++count)
    vertices += frame::patchTessLevels(patches, p, viewProjection, viewport, o).vertexCount();
  return std::max(1.0, std::sqrt(vertices / count) - 1.0);
}

const char* toString(EffectKind kind) {
  switch (kind) {
    case EffectKind::Frustum:
      return "frustum";
    case EffectKind::BackPatch:
      return "back-patch";
    case EffectKind::Accuracy:
      return "accuracy";
    case EffectKind::Occlusion:
      return "occlusion";
    case EffectKind::Passes:
      return "passes";
    case EffectKind::HiZ:
      return "hi-z";
    case EffectKind::Update:
      return "update";
    case EffectKind::Bounds:
      return "bounds";
    case EffectKind::Displacement:
      return "displacement";
  }
  return "?";
}

std::vector<std::pair<EffectKind, const Effect*>> Plan::effects() const {
  return {{EffectKind::Frustum, &frustum},
          {EffectKind::BackPatch, &backPatch},
          {EffectKind::Accuracy, &accuracy},
          {EffectKind::Occlusion, &occlusion},
          {EffectKind::Passes, &passes},
          {EffectKind::HiZ, &hiz},
          {EffectKind::Update, &update},
          {EffectKind::Bounds, &bounds},
          {EffectKind::Displacement, &displacement}};
}

const Effect& Plan::effect(EffectKind kind) const {
  for (const auto& [k, e] : effects())
    if (k == kind) return *e;
  throw Error(std::string("plan: no effect ") + toString(kind));
}

Planner::Planner(Calibration calibration, PlannerOptions options)
    : calibration_(std::move(calibration)), options_(std::move(options)) {
  if (!(options_.margin >= 0.0 && options_.margin < 1.0))
    throw Error("planner: margin must be in [0, 1), got " + std::to_string(options_.margin));
  if (!(options_.learnWeight > 0.0 && options_.learnWeight <= 1.0))
    throw Error("planner: learnWeight must be in (0, 1], got " +
                std::to_string(options_.learnWeight));
  if (options_.scaleWindow == 0) throw Error("planner: scaleWindow must be at least 1 frame");
  calibration_.drawMs(1.0);  // throws without draw costs
  if (options_.accuracy != "auto" && options_.accuracy != "bound" &&
      options_.accuracy != "listed" && options_.accuracy != "surface")
    throw Error("planner: accuracy must be auto, bound, listed or surface, got '" +
                options_.accuracy + "'");
  if (!(options_.listedRateFactor > 0.0 && options_.surfaceRateFactor > 0.0))
    throw Error("planner: the listed and surface rate factors must be positive");
}

RateKey RateKey::frustum() { return {}; }

RateKey RateKey::backPatch(std::string method, Accuracy accuracy) {
  RateKey k;
  k.stage = CullStage::BackPatch;
  k.method = std::move(method);
  k.accuracy = accuracy;
  return k;
}

RateKey RateKey::occlusion(std::string kernel, bool hizFull, bool hizTight) {
  RateKey k;
  k.stage = CullStage::Occlusion;
  k.method = std::move(kernel);
  k.hizFull = hizFull;
  k.hizTight = hizTight;
  return k;
}

RateKey RateKey::occlusion(const StageChoice& stages) {
  return occlusion(stages.occlusion, stages.hizFull, stages.hizTight);
}

RateKey RateKey::parse(const std::string& name) {
  std::vector<std::string> parts;
  for (size_t at = 0;;) {
    const size_t slash = name.find('/', at);
    parts.push_back(name.substr(at, slash == std::string::npos ? slash : slash - at));
    if (slash == std::string::npos) break;
    at = slash + 1;
  }
  const std::string& method = parts.front();
  if (method.empty()) throw Error("planner: a stage name is empty");
  if (method == toString(CullStage::Frustum)) {
    if (parts.size() > 1) throw Error("planner: the frustum stage has no variant: '" + name + "'");
    return frustum();
  }
  static const std::vector<std::string> methods = frame::cullMethodNames(CullStage::BackPatch);
  if (std::find(methods.begin(), methods.end(), method) != methods.end()) {
    if (parts.size() == 1) return backPatch(method);
    if (parts.size() == 2 && parts[1] == toString(Accuracy::Listed))
      return backPatch(method, Accuracy::Listed);
    if (parts.size() == 2 && parts[1] == toString(Accuracy::Surface))
      return backPatch(method, Accuracy::Surface);
    throw Error("planner: '" + name + "': a back-patch accuracy is listed or surface");
  }
  RateKey k = occlusion(method);
  for (size_t i = 1; i < parts.size(); ++i) {
    if (parts[i] == "full" && !k.hizFull && !k.hizTight)
      k.hizFull = true;
    else if (parts[i] == "tight" && !k.hizTight)
      k.hizTight = true;
    else
      throw Error("planner: '" + name + "': an occlusion variant is full, tight or full/tight");
  }
  return k;
}

std::string RateKey::name() const {
  switch (stage) {
    case CullStage::Frustum:
      return toString(CullStage::Frustum);
    case CullStage::BackPatch:
      return accuracy == Accuracy::Bound ? method : method + "/" + toString(accuracy);
    case CullStage::Occlusion:
      return method + (hizFull ? "/full" : "") + (hizTight ? "/tight" : "");
  }
  return "?";
}

RateKey RateKey::plain() const {
  RateKey k = *this;
  k.accuracy = Accuracy::Bound;
  k.hizFull = k.hizTight = false;
  return k;
}

std::vector<Accuracy> Planner::accuracies(const PlanInput& input, const std::string& method) const {
  if (!input.ownAccuracy) return {Accuracy::Bound};
  const bool listed = calibration_.listedCullMsPerPatch.count(method) > 0;
  if (options_.accuracy == "surface")
    return calibration_.surfaceCullMsPerPatch.count(method) ? std::vector{Accuracy::Surface}
                                                            : std::vector<Accuracy>{};
  if (options_.accuracy == "listed")
    return listed ? std::vector{Accuracy::Listed} : std::vector<Accuracy>{};
  if (options_.accuracy == "bound" || !listed) return {Accuracy::Bound};
  return {Accuracy::Bound, Accuracy::Listed};
}

CostCase Planner::costCase(const PlanInput& input, const StageChoice& stages) const {
  CostCase c;
  c.bezier = input.bezier;
  c.gregory = input.gregory;
  c.tess = input.tess;
  c.pixels = uint64_t(input.camera.width) * input.camera.height;
  c.tessFactorZero = options_.tessFactorZero;
  c.pointUpdate = input.deforming && input.cageMoved;
  c.gpuPointUpdate = calibration_.pointUpdateGpuMsPerPatch < calibration_.pointUpdateCpuMsPerPatch;
  // Every back-patch method reads per-patch data the bounds pass recomputes from the moved
  // points (see hasBoundsPass): its pass is charged to it.
  c.boundsPass = c.pointUpdate && !stages.backPatch.empty();
  c.boundsMethod = c.boundsPass ? stages.backPatch : "";
  // A deforming displaced mesh: the displaced kernel its stages test needs the per-frame
  // cones of its extension (ACoN, CoN; the Full bound only the static ranges), recomputed
  // by the displaced bounds pass (issue 10), which is charged to it.
  if (c.pointUpdate && input.displaced && stages.any()) {
    const std::string extension = displacedExtensionOf(displacedBoundsKernel(input, stages));
    if (extension != bound::toString(bound::DisplacedExtension::Full)) {
      c.boundsPass = true;
      c.boundsMethod = extension;
    }
  }
  c.displaced = input.displaced;
  return c;
}

std::vector<std::string> Planner::occlusionKernels(const PlanInput& input) const {
  if (!input.displaced) return {"hiz"};
  // A displaced mesh: every calibrated displaced bound (Niessner & Loop Table 1), chosen by
  // predicted cost; none calibrated: the configured one (then not offered).
  std::vector<std::string> out;
  for (const frame::CullMethod& m : frame::displacedCullMethods())
    if (calibration_.cullMsPerPatch.count(m.name)) out.push_back(m.name);
  if (out.empty()) out.push_back(options_.displacedKernel);
  return out;
}

std::string Planner::displacedBoundsKernel(const PlanInput& input,
                                           const StageChoice& stages) const {
  if (!stages.occlusion.empty()) return stages.occlusion;
  // The frustum stage alone tests the same on any displaced bound: the one whose bounds
  // pass costs least (the Full bound's none).
  std::string best;
  double bestMs = std::numeric_limits<double>::infinity();
  for (const std::string& kernel : occlusionKernels(input)) {
    const std::string extension = displacedExtensionOf(kernel);
    const double ms = extension == bound::toString(bound::DisplacedExtension::Full)
                          ? 0.0
                          : calibration_.boundsMs(extension);
    if (ms < bestMs) {
      bestMs = ms;
      best = kernel;
    }
  }
  return best;
}

std::string Planner::occlusionKernel(const PlanInput& input) const {
  return occlusionKernels(input).front();
}

std::string Planner::bestOcclusionKernel(const PlanInput& input, const State& state,
                                         const StageChoice& stages, BoxInView box) const {
  std::string best;
  double bestMs = std::numeric_limits<double>::infinity();
  for (const std::string& kernel : occlusionKernels(input)) {
    if (!calibration_.cullMsPerPatch.count(kernel)) continue;
    StageChoice with = stages;
    with.occlusion = kernel;
    const double ms =
        predict(calibration_, costCase(input, with), with, ratesFor(state, with, box)).totalMs();
    if (ms < bestMs) {
      bestMs = ms;
      best = kernel;
    }
  }
  return best.empty() ? occlusionKernel(input) : best;
}

bool Planner::offersOcclusion(const PlanInput& input) const {
  if (!input.occluders && !input.selfOccluding) return false;
  for (const std::string& kernel : occlusionKernels(input))
    if (calibration_.cullMsPerPatch.count(kernel)) return true;
  return false;
}

std::vector<StageChoice> Planner::candidates(const PlanInput& input) const {
  std::vector<std::pair<std::string, Accuracy>> backPatch = {{"", Accuracy::Bound}};
  if (input.backPatchValidity.enabled && !input.displaced)
    for (const std::string& m : frame::cullMethodNames(frame::CullStage::BackPatch))
      if (calibration_.cullMsPerPatch.count(m) && (!input.deforming || hasBoundsPass(m)) &&
          (options_.backPatchMethods.empty() ||
           std::find(options_.backPatchMethods.begin(), options_.backPatchMethods.end(), m) !=
               options_.backPatchMethods.end()))
        for (Accuracy a : accuracies(input, m)) backPatch.push_back({m, a});
  std::vector<std::string> occlusion = {""};
  if (offersOcclusion(input))
    for (const std::string& kernel : occlusionKernels(input))
      if (calibration_.cullMsPerPatch.count(kernel)) occlusion.push_back(kernel);
  // The pyramid (Hi-Z resolution, lookup): the paper's (half, paper lookup); in the mesh
  // form also full resolution, and the tight lookup when calibrated.
  using Pyramid = std::pair<bool, bool>;  // full resolution, tight lookup
  std::vector<Pyramid> pyramids = {{false, false}};
  if (input.ownAccuracy) {
    pyramids.push_back({true, false});
    if (calibration_.hizTightMsPerPatch)
      pyramids.insert(pyramids.end(), {{false, true}, {true, true}});
  }
  const std::vector<Pyramid> noPyramid = {{false, false}};
  std::vector<StageChoice> out;
  for (bool frustum : {false, true})
    for (const auto& [b, a] : backPatch)
      for (const std::string& o : occlusion)
        for (const auto& [full, tight] : o.empty() ? noPyramid : pyramids) {
          StageChoice c{frustum, b, o};
          c.accuracy = a;
          c.hizFull = full;
          c.hizTight = tight;
          out.push_back(c);
          if (!o.empty() && options_.allowAggressive) {
            c.aggressive = true;
            out.push_back(c);
          }
        }
  return out;
}

double Planner::stageRate(const State& state, const RateKey& stage) const {
  if (const auto it = state.rates.find(stage); it != state.rates.end()) return it->second;
  // Not measured, but another variant of its stage is (another back-patch method or
  // accuracy, another pyramid): that measurement scaled by the priors' ratio, never above
  // it. A prior is a figure of other meshes; the sibling's rate is this mesh's, so an
  // unmeasured variant is never preferred for its prior alone (issue 18: at tess 16 the
  // plan went from the measured NCONE to tangent-plane-16 and TCONE on their priors, each
  // a new frame).
  const std::optional<RateKey>& sibling =
      stage.stage == CullStage::BackPatch   ? state.lastBackPatchKey
      : stage.stage == CullStage::Occlusion ? state.lastOcclusionKey
                                            : std::nullopt;
  if (sibling)
    if (const auto it = state.rates.find(*sibling); it != state.rates.end())
      return it->second * std::min(1.0, priorRate(stage) / std::max(priorRate(*sibling), 1e-9));
  return priorRate(stage);
}

double Planner::priorRate(const RateKey& stage) const {
  const RateKey plain = stage.plain();
  double rate = 0.0;
  if (const auto it = options_.priorRates.find(plain.name()); it != options_.priorRates.end())
    rate = it->second;
  else if (stage.stage == CullStage::Occlusion)  // a displaced kernel without its own prior
    rate = options_.priorRates.count("hiz") ? options_.priorRates.at("hiz") : 0.0;
  // A back-patch method at another accuracy, an occlusion kernel on another pyramid: its
  // plain prior times each variant's factor, at most 1.
  const double factor = (stage.accuracy == Accuracy::Listed    ? options_.listedRateFactor
                         : stage.accuracy == Accuracy::Surface ? options_.surfaceRateFactor
                                                               : 1.0) *
                        (stage.hizFull ? options_.fullRateFactor : 1.0) *
                        (stage.hizTight ? options_.tightRateFactor : 1.0);
  return std::min(1.0, factor * rate);
}

CullRates Planner::ratesFor(const State& state, const StageChoice& stages, BoxInView box) const {
  CullRates r;
  r.frustum = box == BoxInView::Outside  ? 1.0
              : box == BoxInView::Inside ? 0.0
                                         : stageRate(state, RateKey::frustum());
  if (!stages.backPatch.empty())
    r.backPatch = stageRate(state, RateKey::backPatch(stages.backPatch, stages.accuracy));
  if (stages.accuracy == Accuracy::Listed) {
    // The listed test runs where the surface test culls and the bound keeps; of those it
    // culls 74-100% (docs/results/accuracy-vs-time.md, BigGuy tess 4-16: (listed - bound) /
    // (surface - bound)). Dividing its gain over the bound by 0.74 keeps the share of runs,
    // and so its predicted cost, on the high side.
    const double bound = stageRate(state, RateKey::backPatch(stages.backPatch));
    r.listedRuns = std::clamp((r.backPatch - bound) / 0.74, 0.0, 1.0 - bound);
  }
  if (!stages.occlusion.empty()) r.occlusion = stageRate(state, RateKey::occlusion(stages));
  return r;
}

double Planner::rate(const std::string& key, const RateKey& stage) const {
  const auto it = states_.find(key);
  static const State empty;
  return stageRate(it == states_.end() ? empty : it->second, stage);
}

double Planner::rate(const std::string& key, const std::string& stage) const {
  return rate(key, RateKey::parse(stage));
}

double Planner::predictedMs(const State& s, const PlanInput& input, const StageChoice& c,
                            BoxInView box) const {
  return scaled(predict(calibration_, costCase(input, c), c, ratesFor(s, c, box)),
                s.drawScaleFor(c), s.cullScaleNow())
      .totalMs();
}

// A probe's next interval: twice `interval`, at most PlannerOptions::maxReprobeFrames (or
// `first`, the kind's first interval, where that is longer).
uint32_t Planner::doubledInterval(uint32_t interval, uint32_t first) const {
  return std::min(std::max(options_.maxReprobeFrames, first), 2 * interval);
}

// Whether a choice predicted at `culledMs` against `unculledMs` without culling saves too
// little for the prediction to be sure of it (PlannerOptions::unculledCheckBelow): then the
// unculled checks run.
bool Planner::uncertainSaving(double culledMs, double unculledMs) const {
  return culledMs > (1.0 - options_.unculledCheckBelow) * unculledMs;
}

// Steps 2 and 3 of the plan (planner.h): the cheapest predicted choice, or while exploring
// the cheapest that runs every stage kind offered; the current one is kept unless the new one
// is predicted cheaper by the margin after the hold. Returns whether this frame explores.
bool Planner::choose(State& s, const PlanInput& input, const std::vector<StageChoice>& all, Plan& p,
                     uint64_t frameNumber) const {
  auto total = [&](const StageChoice& c) { return predictedMs(s, input, c, p.box); };
  const StageChoice best = *std::min_element(
      all.begin(), all.end(),
      [&](const StageChoice& a, const StageChoice& b) { return total(a) < total(b); });
  if (!s.firstFrame) s.firstFrame = frameNumber;
  if (frameNumber - *s.firstFrame < options_.exploreFrames) {
    // Exploring: every stage kind offered at once, the cheapest predicted such choice; it
    // becomes the current choice, held as long as nothing is predicted cheaper by the margin.
    std::optional<StageChoice> every;
    const bool anyBackPatch = std::any_of(
        all.begin(), all.end(), [](const StageChoice& c) { return !c.backPatch.empty(); });
    for (const StageChoice& c : all)
      if (c.frustum == (p.box != BoxInView::Inside) && c.backPatch.empty() != anyBackPatch &&
          c.occlusion.empty() != offersOcclusion(input) && !c.aggressive &&
          (!every || total(c) < total(*every)))
        every = c;
    if (every) {
      s.current = *every;
      s.since = frameNumber;
      s.explored = true;  // the first choice after it is not held
    }
  }
  const bool exploring = s.explored && frameNumber - *s.firstFrame < options_.exploreFrames;
  // Right after exploring, PlannerOptions::unculledFirstChecks frames with no stage at all
  // (the unculled check, PlannerOptions::unculledCheckFrames) when the explored choice culls:
  // the choice after them compares measured frames. The frame after them is still unheld.
  if (s.explored && !exploring &&
      frameNumber - *s.firstFrame < options_.exploreFrames + options_.unculledFirstChecks &&
      options_.unculledCheckFrames > 0 && s.current && s.current->any() &&
      p.box != BoxInView::Outside && uncertainSaving(total(*s.current), total({}))) {
    p.stages = {};
    p.probe = p.unculledCheck = true;
    return true;
  }
  // The first choice after exploring is made on the measured rates, not held.
  const bool unheld = s.explored && !exploring;
  if (unheld) s.explored = false;
  const bool valid = s.current && std::find(all.begin(), all.end(), *s.current) != all.end();
  // Hysteresis: the margin grows with each change of the last window, so two choices
  // predicted alike (within the rates' noise) cannot take turns.
  const double margin = std::min(0.5, options_.margin * (1.0 + double(s.switches.size())));
  if (!valid) {
    s.current = best;
    s.since = frameNumber;
  } else if (!(best == *s.current) && (unheld || frameNumber - s.since >= options_.holdFrames) &&
             total(best) < (1.0 - margin) * total(*s.current)) {
    s.current = best;
    s.since = frameNumber;
    s.switches.push_back(frameNumber);
  }
  p.stages = *s.current;
  p.probe = exploring;
  return exploring;
}

// Step 4 of the plan: one switched-off stage runs now and then (a re-probe), because its rate
// is learned only while it runs.
void Planner::reprobe(State& s, const PlanInput& input, const std::vector<StageChoice>& all,
                      Plan& p, uint64_t frameNumber, bool exploring) const {
  auto total = [&](const StageChoice& c) { return predictedMs(s, input, c, p.box); };
  // The unculled frame is checked at the end (Plan::unculledCheck): a frame with no stage
  // keeps every cull configuration and its visibility status (MeshSession's cache).
  for (CullStage kind : {CullStage::Frustum, CullStage::BackPatch, CullStage::Occlusion})
    if (!s.lastRun.count(kind)) s.lastRun[kind] = frameNumber;
  if (exploring) {
    // Every kind runs already.
  } else if (s.hold) {
    // An occlusion probe's second frame: its first ran on a status that had not seen the
    // stage (the rate it counted is not learned), this one measures it.
    p.stages = *s.hold;
    p.probe = true;
    s.hold.reset();
  } else if (options_.reprobeFrames > 0) {
    std::string probeBackPatch;
    Accuracy probeAccuracy = Accuracy::Bound;
    double probeRate = -1.0;
    for (const StageChoice& c : all)
      if (!c.backPatch.empty() &&
          stageRate(s, RateKey::backPatch(c.backPatch, c.accuracy)) > probeRate) {
        probeRate = stageRate(s, RateKey::backPatch(c.backPatch, c.accuracy));
        probeBackPatch = c.backPatch;
        probeAccuracy = c.accuracy;
      }
    auto interval = [&](CullStage kind) {
      const bool prior = !s.measured.count(kind) && options_.firstProbeFrames > 0;
      if (prior) return std::min(options_.firstProbeFrames, options_.reprobeFrames);
      const auto it = s.probeInterval.find(kind);
      return it == s.probeInterval.end() ? options_.reprobeFrames : it->second;
    };
    auto due = [&](CullStage kind) { return frameNumber - s.lastRun[kind] >= interval(kind); };
    // A probe doubles the kind's interval (up to maxReprobeFrames): a steady view probes
    // ever more rarely, until its inputs change.
    auto probed = [&](CullStage kind) {
      if (s.measured.count(kind))
        s.probeInterval[kind] = doubledInterval(interval(kind), options_.reprobeFrames);
      p.probe = true;
    };
    if (!p.stages.frustum && p.box == BoxInView::Crossing && due(CullStage::Frustum)) {
      p.stages.frustum = true;
      probed(CullStage::Frustum);
    } else if (p.stages.backPatch.empty() && !probeBackPatch.empty() && due(CullStage::BackPatch)) {
      p.stages.backPatch = probeBackPatch;
      p.stages.accuracy = probeAccuracy;
      probed(CullStage::BackPatch);
    } else if (p.stages.occlusion.empty() && offersOcclusion(input) && due(CullStage::Occlusion)) {
      // The occlusion kernel and pyramid predicted cheapest with the other stages as planned
      // (so the probe measures what would be switched on).
      std::optional<StageChoice> with;
      for (const StageChoice& c : all)
        if (!c.occlusion.empty() && c.frustum == p.stages.frustum &&
            c.backPatch == p.stages.backPatch && c.accuracy == p.stages.accuracy && !c.aggressive &&
            (!with || total(c) < total(*with)))
          with = c;
      if (with) {
        p.stages = *with;
      } else {
        p.stages.occlusion = occlusionKernel(input);
      }
      probed(CullStage::Occlusion);
      s.hold = p.stages;
    }
  }
  // The unculled check (PlannerOptions::unculledCheckFrames) where no stage probe runs.
  // (The predictions last: only on a frame the check is due.)
  if (!exploring && !p.probe && options_.unculledCheckFrames > 0 && p.stages.any() &&
      p.box != BoxInView::Outside) {
    const uint32_t interval =
        s.unculledInterval > 0 ? s.unculledInterval : options_.unculledCheckFrames;
    if (frameNumber - s.lastUnculled >= interval && uncertainSaving(total(p.stages), total({}))) {
      p.stages = {};
      p.probe = p.unculledCheck = true;
      s.unculledInterval = doubledInterval(interval, options_.unculledCheckFrames);
    }
  }
}

Plan Planner::plan(const std::string& key, const PlanInput& input, uint64_t frameNumber) {
  State& s = states_[key];
  if (s.current && frameNumber < s.lastFrame)
    throw Error("planner: frame " + std::to_string(frameNumber) + " of '" + key +
                "' comes after frame " + std::to_string(s.lastFrame));
  s.lastFrame = frameNumber;
  // New inputs (another level, image size, motion): the re-probes start over.
  if (const std::string inputs = inputsSignature(input); inputs != s.inputs) {
    s.inputs = inputs;
    s.probeInterval.clear();
    s.unculledInterval = 0;
    s.lastUnculled = frameNumber;
  }
  while (!s.switches.empty() && frameNumber - s.switches.front() >= options_.oscillationWindow)
    s.switches.pop_front();
  Plan p;
  p.mesh = input.mesh;
  p.view = input.view;
  p.frame = frameNumber;
  p.box = boxInView(input.objectBounds, input.model, input.camera);
  const std::vector<StageChoice> all = candidates(input);
  const bool exploring = choose(s, input, all, p, frameNumber);
  reprobe(s, input, all, p, frameNumber, exploring);
  if (options_.countingProbes && frameNumber == *s.firstFrame)
    for (const StageChoice& c : all)
      if (!c.backPatch.empty() && c.frustum == p.stages.frustum && c.occlusion.empty() &&
          !(c.backPatch == p.stages.backPatch && c.accuracy == p.stages.accuracy) &&
          !s.rates.count(RateKey::backPatch(c.backPatch, c.accuracy)))
        p.countOnly.push_back(c);
  if (!p.stages.any()) s.lastUnculled = frameNumber;
  if (p.stages.frustum) s.lastRun[CullStage::Frustum] = frameNumber;
  if (!p.stages.backPatch.empty()) s.lastRun[CullStage::BackPatch] = frameNumber;
  if (!p.stages.occlusion.empty()) s.lastRun[CullStage::Occlusion] = frameNumber;

  p.rates = ratesFor(s, p.stages, p.box);
  p.drawScale = s.drawScaleFor(p.stages);
  p.cullScale = s.cullScaleNow();
  p.cost = costCase(input, p.stages);
  p.predicted = scaled(predict(calibration_, p.cost, p.stages, p.rates), p.drawScale, p.cullScale);
  p.predictedUnculled = scaled(predict(calibration_, costCase(input, {}), {}, p.rates),
                               s.unculledScaleNow(), p.cullScale);
  explain(p, input, s);
  return p;
}

// The reasons of a plan, one function per effect: each returns the effect's on/off and
// choice (from the plan's stages, decided in plan()), its predicted change of the frame
// time, and the sentence that opens with the decision those numbers make (decision()), so
// that the printed reason cannot contradict the effect.
struct Planner::Explaining {
  const Planner& planner;
  const Plan& p;
  const PlanInput& input;
  const State& s;
  const Calibration& calibration;
  const CostCase base;
  const double n;   // patches
  const double rt;  // draw cost of a patch (RT), and of a back-facing one
  const double rtBack;
  const double rt0;  // of a culled patch drawn with tessellation factor 0
  const double now;  // the planned frame, predicted
  const double k;    // the effects' ms in this machine's measured time

  Explaining(const Planner& of, const Plan& plan, const PlanInput& in, const State& state)
      : planner(of),
        p(plan),
        input(in),
        s(state),
        calibration(planner.calibration_),
        base(planner.costCase(input, plan.stages)),
        n(std::max(1u, base.patches())),
        rt(drawMsPerPatch(calibration, base)),
        rtBack(std::min(rt, backDrawMsPerPatch(calibration, base))),
        rt0(planner.options_.tessFactorZero ? calibration.drawZeroMsPerPatch : 0.0),
        now(total(plan.stages)),
        k(plan.drawScale) {}

  double total(const StageChoice& c) const { return planner.predictedMs(s, input, c, p.box); }
  const char* source(const RateKey& stage) const {
    return s.rates.count(stage) ? "measured" : "prior";
  }
  double rate(const RateKey& stage) const { return planner.stageRate(s, stage); }
  std::string tessText() const { return " at tess " + std::to_string(int(input.tess)); }

  // The break-even rate of adding `with` to `without` (§6.3), fixed costs spread per patch;
  // a patch the stage culls would have cost `saved` (RT, or RT of a back-facing patch).
  double breakEven(const StageChoice& with, const StageChoice& without, double saved) const {
    const Prediction a = predict(calibration, planner.costCase(input, with), with, {});
    const Prediction b = predict(calibration, planner.costCase(input, without), without, {});
    const double ct = (a.cullMs + a.hizMs + a.updateMs - b.cullMs - b.hizMs - b.updateMs) / n;
    return breakEvenRate(saved, rt0, ct);
  }
  std::string stageReason(const RateKey& stage, double r, const StageChoice& with,
                          const StageChoice& without) const {
    const bool occlusion = with.occlusion != without.occlusion;
    const double x = breakEven(with, without, occlusion ? rt : rtBack);
    return std::string(source(stage)) + " rate " + percent(r) + " against break-even " +
           (std::isfinite(x) ? percent(x) : std::string("(never)")) + tessText();
  }
  // The one sentence of a stage's decision, from the numbers that made it (deltaMs: the
  // predicted change of the frame the stage makes, on; or would make, off): it saves, it
  // would cost, it is a re-probe, or the hysteresis holds the current choice against a
  // prediction that now favours the other.
  std::string decision(bool on, double deltaMs, bool probed) const {
    char text[160];
    if (p.unculledCheck)
      std::snprintf(text, sizeof text,
                    "unculled check: one frame with no stage, to measure the frame without "
                    "culling (%+.2f ms)",
                    deltaMs);
    else if (probed)
      std::snprintf(text, sizeof text, "re-probe: runs once to measure its rate (%+.2f ms)",
                    deltaMs);
    else if (on && deltaMs <= 0.0)
      std::snprintf(text, sizeof text, "saves %.2f ms", -deltaMs);
    else if (!on && deltaMs >= 0.0)
      std::snprintf(text, sizeof text, "would cost %.2f ms", deltaMs);
    else
      std::snprintf(text, sizeof text,
                    "kept %s by the hysteresis: %s would save %.2f ms, but a change needs "
                    "%.0f%% of the frame after %u frames held",
                    on ? "on" : "off", on ? "off" : "on", std::abs(deltaMs),
                    100.0 * planner.options_.margin, planner.options_.holdFrames);
    return std::string(text) + "; ";
  }

  Effect frustum() const {
    StageChoice off = p.stages, on = p.stages;
    off.frustum = false;
    on.frustum = true;
    Effect e;
    e.on = p.stages.frustum;
    e.deltaMs = e.on ? now - total(off) : total(on) - now;
    if (p.box == BoxInView::Outside)
      e.reason = "object box outside the view (Sathe pre-test): culls every patch";
    else if (p.box == BoxInView::Inside)
      e.reason = "object box inside the view (Sathe pre-test): would cull nothing";
    else
      e.reason =
          decision(e.on, e.deltaMs, p.probe && e.on && (s.explored || !s.current->frustum)) +
          stageReason(RateKey::frustum(),
                      p.rates.frustum > 0 ? p.rates.frustum : rate(RateKey::frustum()), on, off);
    return e;
  }

  Effect backPatch() const {
    Effect e;
    e.on = !p.stages.backPatch.empty();
    e.choice = p.stages.backPatch;
    StageChoice off = p.stages;
    off.backPatch.clear();
    off.accuracy = Accuracy::Bound;
    if (input.displaced) {
      e.reason = "displaced mesh: the back-patch tests bound the undisplaced surface";
    } else if (!input.backPatchValidity.enabled) {
      e.reason = input.backPatchValidity.reason;
    } else if (e.on) {
      e.deltaMs = now - total(off);
      e.reason =
          decision(true, e.deltaMs, p.probe && (s.explored || s.current->backPatch.empty())) +
          stageReason(RateKey::backPatch(p.stages.backPatch, p.stages.accuracy), p.rates.backPatch,
                      p.stages, off);
    } else {
      // The best method it could have run.
      std::optional<StageChoice> best;
      for (const StageChoice& c : planner.candidates(input))
        if (!c.backPatch.empty() && c.frustum == p.stages.frustum &&
            c.occlusion == p.stages.occlusion && c.aggressive == p.stages.aggressive &&
            (!best || total(c) < total(*best)))
          best = c;
      if (!best) {
        e.reason = input.deforming ? "deforming mesh: no calibrated method with a bounds pass "
                                     "(tcone, ncone, tangent-plane)"
                                   : "no back-patch method calibrated";
      } else {
        StageChoice with = p.stages;
        with.backPatch = best->backPatch;
        with.accuracy = best->accuracy;
        const RateKey key = RateKey::backPatch(best->backPatch, best->accuracy);
        e.choice = best->backPatch;
        e.deltaMs = total(*best) - now;
        e.reason = decision(false, e.deltaMs, false) + best->backPatch + " " +
                   stageReason(key, rate(key), with, p.stages);
      }
    }
    return e;
  }

  // Accuracy of the back-patch test: the bound or the listed triangles by predicted cost,
  // surface-exact only when asked for.
  Effect accuracy() const {
    Effect e;
    e.on = !p.stages.backPatch.empty();
    if (!e.on) {
      e.reason = "no back-patch stage";
      return e;
    }
    const Accuracy a = p.stages.accuracy;
    e.choice = toString(a);
    auto at = [&](Accuracy other) {
      StageChoice c = p.stages;
      c.accuracy = other;
      return c;
    };
    auto line = [&](Accuracy other) {
      const RateKey key = RateKey::backPatch(p.stages.backPatch, other);
      return std::string(toString(other)) + " " + source(key) + " " + percent(rate(key)) +
             " predicted " + ms(total(at(other)));
    };
    const std::string& asked = planner.options_.accuracy;
    if (!input.ownAccuracy) {
      e.reason =
          "drawn-triangle bound: the scene's one cull frame per view applies "
          "one accuracy to every instance";
    } else if (a == Accuracy::Surface) {
      e.reason =
          "surface-exact asked for (the papers' test): NOT conservative for the drawn chord "
          "triangles, can lose silhouette pixels; " +
          line(a);
    } else if (asked != "auto") {
      e.reason = std::string(toString(a)) + " asked for (conservative for the drawn triangles); " +
                 line(a);
    } else if (!calibration.listedCullMsPerPatch.count(p.stages.backPatch)) {
      e.reason =
          "drawn-triangle bound: the listed test of " + p.stages.backPatch + " is not calibrated";
    } else {
      const Accuracy other = a == Accuracy::Bound ? Accuracy::Listed : Accuracy::Bound;
      e.deltaMs = a == Accuracy::Listed ? now - total(at(other)) : total(at(other)) - now;
      char ct[96];
      std::snprintf(ct, sizeof ct, "listed test +%.3f us per patch it runs on",
                    1e3 * calibration.listedCullMs(p.stages.backPatch, input.tess));
      e.reason =
          std::string(a == Accuracy::Listed ? "listed triangles pay" : "the bound is cheaper") +
          tessText() + " (" + ct + "): " + line(a) + " against " + line(other) +
          "; both conservative for the drawn triangles";
    }
    return e;
  }

  Effect occlusion() const {
    Effect e;
    e.on = !p.stages.occlusion.empty();
    e.choice = p.stages.occlusion;
    const std::string kernel =
        e.on ? p.stages.occlusion : planner.bestOcclusionKernel(input, s, p.stages, p.box);
    StageChoice with = p.stages, without = p.stages;
    with.occlusion = kernel;
    without.occlusion.clear();
    if (!input.occluders && !input.selfOccluding) {
      e.reason =
          "nothing can hide it in this view (no occluders, no other instance) and its surface "
          "is convex (cannot hide itself)";
    } else if (!calibration.cullMsPerPatch.count(kernel)) {
      e.reason = "the cost of kernel " + kernel + " is not in the calibration";
    } else {
      e.choice = kernel;
      e.deltaMs = e.on ? now - total(without) : total(with) - now;
      // Alone in the view, only the mesh itself can hide its patches: the self-occlusion
      // rule (a non-convex surface), learned from its own frames like the other stages.
      const RateKey key = RateKey::occlusion(with);
      e.reason = decision(e.on, e.deltaMs,
                          p.probe && e.on && (s.explored || s.current->occlusion.empty())) +
                 (input.occluders ? std::string() : "self-occlusion (non-convex surface): ") +
                 stageReason(key, rate(key), with, without) + " (Hi-Z build included)";
    }
    return e;
  }

  Effect passes() const {
    Effect e;
    e.on = !p.stages.occlusion.empty();
    e.choice = e.on ? (p.stages.aggressive ? "aggressive" : "two-pass") : "one";
    e.reason = !e.on ? "no occlusion: one pass"
               : p.stages.aggressive
                   ? "aggressive (§3.1): newly visible patches appear a frame late"
                   : "two-pass (§3): the same image as without culling";
    return e;
  }

  static std::string pyramid(const StageChoice& c) {
    return std::string(c.hizFull ? "full" : "half") + (c.hizTight ? "/tight" : "/paper");
  }

  Effect hiz() const {
    Effect e;
    e.on = !p.stages.occlusion.empty();
    const uint64_t pixels = uint64_t(input.camera.width) * input.camera.height;
    e.choice = e.on ? pyramid(p.stages) : "";
    e.deltaMs = e.on ? calibration.hizBuildMs(hizPixels(pixels, p.stages.hizFull)) : 0.0;
    const std::string builds = "build half " +
                               ms(calibration.hizBuildMs(hizPixels(pixels, false))) + ", full " +
                               ms(calibration.hizBuildMs(hizPixels(pixels, true)));
    if (!e.on) {
      e.reason = "no occlusion: no pyramid";
    } else if (!input.ownAccuracy) {
      e.reason =
          "the scene's one pyramid per view: level 0 at half resolution, the paper's "
          "lookup (Niessner & Loop §4.1); " +
          builds;
    } else {
      // Every pyramid variant of the same stages: predicted frame and rate.
      std::string variants;
      for (const StageChoice& c : planner.candidates(input))
        if (c.occlusion == p.stages.occlusion && c.frustum == p.stages.frustum &&
            c.backPatch == p.stages.backPatch && c.accuracy == p.stages.accuracy &&
            c.aggressive == p.stages.aggressive)
          variants += (variants.empty() ? "" : ", ") + pyramid(c) + " " + ms(total(c)) + " (" +
                      source(RateKey::occlusion(c)) + " " + percent(rate(RateKey::occlusion(c))) +
                      ")";
      char tight[64] = "tight lookup not calibrated";
      if (calibration.hizTightMsPerPatch)
        std::snprintf(tight, sizeof tight, "tight lookup +%.3f us/patch",
                      1e3 * *calibration.hizTightMsPerPatch);
      e.reason = "cheapest predicted of " + variants + "; " + builds + ", " + tight;
    }
    return e;
  }

  Effect update() const {
    Effect e;
    e.on = base.pointUpdate;
    e.choice = e.on ? (base.gpuPointUpdate ? "gpu" : "cpu") : "";
    if (!input.deforming) {
      e.reason = "static mesh: control points computed once, never re-evaluated";
    } else if (!input.cageMoved) {
      e.reason = "the cage did not move since the last frame: nothing to update";
    } else {
      e.deltaMs =
          k * n *
          std::min(calibration.pointUpdateCpuMsPerPatch, calibration.pointUpdateGpuMsPerPatch);
      e.reason = "cage moved: cpu " + ms(n * calibration.pointUpdateCpuMsPerPatch) + ", gpu " +
                 ms(n * calibration.pointUpdateGpuMsPerPatch) + " (calibrated); the cheaper runs";
    }
    return e;
  }

  Effect bounds() const {
    Effect e;
    e.on = base.boundsPass;
    e.choice = e.on ? base.boundsMethod : "";
    e.deltaMs = e.on ? k * n * calibration.boundsMs(base.boundsMethod) : 0.0;
    if (!base.pointUpdate)
      e.reason = "points did not move: the cull data stays valid";
    else if (e.on)
      e.reason =
          "recomputes the " + base.boundsMethod +
          (input.displaced ? " cones of the displaced bound" : " cull data") +
          " of the moved points (bounds pass, " + ms(n * calibration.boundsMs(base.boundsMethod)) +
          " calibrated, charged to the " +
          (input.displaced ? "displaced kernel " + planner.displacedBoundsKernel(input, p.stages)
                           : std::string("method")) +
          ")";
    else if (input.displaced)
      e.reason =
          p.stages.any()
              ? "the displaced bound tested (full) needs only the static ranges: no bounds pass"
              : "no cull stage: no bounds pass";
    else
      e.reason = "no back-patch method runs: no bounds pass";
    return e;
  }

  Effect displacement() const {
    Effect e;
    e.on = input.displaced;
    if (!input.displaced) {
      e.reason = "no displacement map: no displacement kernel compiled or bound";
      return e;
    }
    // The displaced bound the frustum and occlusion stages test: the occlusion stage's, or
    // the one predicted cheapest with occlusion (the frustum test alone is the same test on
    // any of them). A deforming mesh whose points moved: the frustum stage alone tests the
    // bound whose bounds pass costs least (displacedBoundsKernel).
    const std::string kernel = !p.stages.occlusion.empty() ? p.stages.occlusion
                               : base.pointUpdate
                                   ? planner.displacedBoundsKernel(input, p.stages)
                                   : planner.bestOcclusionKernel(input, s, p.stages, p.box);
    const auto kernels = planner.occlusionKernels(input);
    const auto measured = std::count_if(
        kernels.begin(), kernels.end(),
        [&](const std::string& name) { return calibration.cullMsPerPatch.count(name) > 0; });
    e.choice = p.stages.any() ? kernel : "draw only";
    char factor[32];
    std::snprintf(factor, sizeof factor, "%.2f", calibration.displacedDrawFactorAt(input.tess));
    const RateKey key = RateKey::occlusion(kernel);
    e.reason = std::string("draw RT(tf) x") + factor + " (calibrated displacement lookup); " +
               (p.stages.any() ? "frustum and occlusion test the " + kernel +
                                     " bound: cheapest predicted of " + std::to_string(measured) +
                                     " calibrated displaced bound" + (measured == 1 ? "" : "s") +
                                     " at " + source(key) + " rate " + percent(rate(key))
                               : std::string("no cull stage: the map is used by the draw only"));
    return e;
  }
};

void Planner::explain(Plan& p, const PlanInput& input, const State& s) const {
  const Explaining e(*this, p, input, s);
  p.frustum = e.frustum();
  p.backPatch = e.backPatch();
  p.accuracy = e.accuracy();
  p.occlusion = e.occlusion();
  p.passes = e.passes();
  p.hiz = e.hiz();
  p.update = e.update();
  p.bounds = e.bounds();
  p.displacement = e.displacement();
}

void Planner::observeCount(const std::string& key, const StageChoice& stages, uint32_t culled,
                           uint32_t total) {
  if (total == 0 || stages.backPatch.empty()) return;
  State& s = states_[key];
  const RateKey k = RateKey::backPatch(stages.backPatch, stages.accuracy);
  learnRate(s.rates, k, double(std::min(culled, total)) / total, options_.learnWeight);
  s.measured.insert(CullStage::BackPatch);
}

void Planner::observe(const std::string& key, const Plan& plan, uint32_t culledFrustum,
                      uint32_t culledBackPatch, uint32_t culledOcclusion, uint32_t total,
                      double measuredMs) {
  Observation o;
  o.culledFrustum = culledFrustum;
  o.culledBackPatch = culledBackPatch;
  o.culledOcclusion = culledOcclusion;
  o.total = total;
  o.ms = measuredMs;
  observe(key, plan, o);
}

void Planner::observe(const std::string& key, const Plan& plan, const Observation& o) {
  if (o.total == 0) return;
  State& s = states_[key];
  // The first frame of a stage choice is not timed into the scales: it is the first run of
  // its passes (pipelines, descriptor sets and buffers first touched), which on lavapipe
  // costs several frames' time. A frame without culling has no pass of its own.
  const bool culls = plan.stages.any();
  const bool warm =
      !culls || std::find(s.observed.begin(), s.observed.end(), plan.stages) != s.observed.end();
  if (!warm) s.observed.push_back(plan.stages);
  // The frame re-predicted at the rates it measured: what the model says it should have
  // cost, to compare with what it did.
  CullRates measured = plan.rates;
  measured.frustum = double(o.culledFrustum) / o.total;
  measured.backPatch = double(o.culledBackPatch) / o.total;
  measured.occlusion = double(o.culledOcclusion) / o.total;
  const Prediction model = predict(calibration_, plan.cost, plan.stages, measured);
  // The draw work follows the patches the frame drew, which the cull counts tell only in a
  // steady view: while the visibility status lags it (the first frames of a choice, a
  // turning camera) pass 1 draws patches that this frame's test then calls occluded, and
  // the frame costs what it drew (issue 18: BigGuy's first culled frames taught a draw
  // scale of 1.6 and every later prediction was 20% high).
  CullRates drawnRates = measured;
  if (o.drawn && !plan.stages.occlusion.empty()) {
    const double notDrawn = 1.0 - double(std::min(*o.drawn, o.total)) / o.total;
    const double facingAway = (plan.stages.frustum ? measured.frustum : 0.0) +
                              (plan.stages.backPatch.empty() ? 0.0 : measured.backPatch);
    drawnRates.occlusion = std::max(0.0, notDrawn - facingAway);
  }
  const Prediction drawnModel = predict(calibration_, plan.cost, plan.stages, drawnRates);
  const double drawModel = drawnModel.drawMs + drawnModel.fixedMs,
               cullModel = model.cullMs + model.hizMs;
  // A scale is the median of the last PlannerOptions::scaleWindow measured ratios: the first
  // replaces the calibration's figure (as a measured rate replaces its prior), and one slow
  // frame (lavapipe runs a frame after a heavy one up to 1.5x slower) moves it not at all.
  auto learnScale = [&](double& scale, bool& known, std::deque<double>& recent, double ratio) {
    if (!std::isfinite(ratio)) return;
    recent.push_back(std::clamp(ratio, 0.05, 20.0));
    while (recent.size() > options_.scaleWindow) recent.pop_front();
    scale = median(recent);
    known = true;
  };
  if (warm && o.ms > 0.0 && std::isfinite(o.ms) && drawModel > 0.0) {
    if (!culls) {
      learnScale(s.unculledScale, s.unculledMeasured, s.unculledRatios, o.ms / drawModel);
    } else if (std::isfinite(o.cullMs) && o.cullMs >= 0.0 && o.cullMs < o.ms) {
      learnScale(s.drawScale, s.drawMeasured, s.drawRatios, (o.ms - o.cullMs) / drawModel);
      if (cullModel > 0.0)
        learnScale(s.cullScale, s.cullMeasured, s.cullRatios, o.cullMs / cullModel);
    } else if (s.drawMeasured && cullModel > 0.0) {
      // Only the total: the draw scale as learned, the rest is the cull work's.
      learnScale(s.cullScale, s.cullMeasured, s.cullRatios,
                 (o.ms - s.drawScale * drawModel) / cullModel);
    } else {
      const double ratio = o.ms / (drawModel + cullModel);
      learnScale(s.drawScale, s.drawMeasured, s.drawRatios, ratio);
      learnScale(s.cullScale, s.cullMeasured, s.cullRatios, ratio);
    }
  }
  auto learn = [&](const RateKey& stage, uint32_t culled) {
    learnRate(s.rates, stage, double(culled) / double(o.total), options_.learnWeight);
  };
  // The frustum's rate is learned only where the pre-test leaves it open.
  if (plan.stages.frustum && plan.box == BoxInView::Crossing) {
    learn(RateKey::frustum(), o.culledFrustum);
    s.measured.insert(CullStage::Frustum);
  }
  if (!plan.stages.backPatch.empty()) {
    s.measured.insert(CullStage::BackPatch);
    s.lastBackPatchKey = RateKey::backPatch(plan.stages.backPatch, plan.stages.accuracy);
    learn(*s.lastBackPatchKey, o.culledBackPatch);
  }
  // The occlusion rate of a choice's first frame is not learned: its visibility status has
  // not seen the stage yet (a new frame starts with nothing visible, or from a status some
  // frames old), so what it culled says little of what the stage culls (the probe's
  // second frame measures it).
  if (!plan.stages.occlusion.empty() && warm) {
    s.measured.insert(CullStage::Occlusion);
    s.lastOcclusionKey = RateKey::occlusion(plan.stages);
    learn(*s.lastOcclusionKey, o.culledOcclusion);
  }
}

frame::CullFrameOptions applyPlan(const Plan& plan, frame::CullFrameOptions base) {
  base.cull.frustum = plan.stages.frustum;
  base.cull.backPatch = plan.stages.backPatch;
  base.cull.drawnTriangles = plan.stages.accuracy != Accuracy::Surface;
  base.cull.drawnEnumerate = plan.stages.accuracy == Accuracy::Listed;
  base.cull.occlusion = plan.stages.occlusion;
  base.aggressive = plan.stages.aggressive;
  base.hiz.fullResolution = plan.stages.hizFull;
  base.hiz.lookup = plan.stages.hizTight ? bound::HiZLookup::Tight : bound::HiZLookup::Paper;
  if (!plan.displacement.on) {
    base.cull.displacementMap = nullptr;
    base.cull.uvCorners = {};
  } else if (plan.stages.any()) {
    // The displaced bound the frustum and occlusion stages test (Plan::displacement).
    const std::string& kernel =
        plan.stages.occlusion.empty() ? plan.displacement.choice : plan.stages.occlusion;
    for (const frame::CullMethod& m : frame::displacedCullMethods())
      if (m.name == kernel) base.cull.displacedKernel = *m.displaced;
  }
  return base;
}

std::string planTable(std::span<const Plan> plans) {
  std::ostringstream out;
  out << "| mesh | view | frame | box | effect | on | choice | predicted ms | reason |\n"
      << "|---|---|---:|---|---|---|---|---:|---|\n";
  char line[64];
  for (const Plan& p : plans) {
    for (const auto& [kind, e] : p.effects()) {
      std::snprintf(line, sizeof line, "%+.2f", e->deltaMs);
      out << "| " << p.mesh << " | " << p.view << " | " << p.frame << " | " << toString(p.box)
          << " | " << toString(kind) << " | " << (e->on ? "on" : "off") << " | "
          << (e->choice.empty() ? "-" : e->choice) << " | " << line << " | " << e->reason << " |\n";
    }
    std::snprintf(line, sizeof line, "%.2f", p.predicted.totalMs());
    out << "| " << p.mesh << " | " << p.view << " | " << p.frame << " | " << toString(p.box)
        << " | **frame** | " << (p.culls() ? "cull" : "no cull") << " | " << p.stages.describe()
        << (p.probe ? " (re-probe)" : "") << " | " << line << " | predicted "
        << ms(p.predicted.totalMs()) << " against " << ms(p.predictedUnculled.totalMs())
        << " without culling; " << percent(p.predicted.culled) << " not drawn |\n";
  }
  return out.str();
}

std::string planChange(const Plan& before, const Plan& after) {
  std::string text;
  const auto a = before.effects(), b = after.effects();
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].second->on != b[i].second->on ||
        (b[i].second->on && a[i].second->choice != b[i].second->choice))
      text += std::string(toString(b[i].first)) + " " + (b[i].second->on ? "on" : "off") +
              (b[i].second->choice.empty() ? "" : " (" + b[i].second->choice + ")") + ": " +
              b[i].second->reason + "\n";
  return text;
}

}  // namespace osd_cull::plan
