#include "osd_cull/plan/cost_model.h"

#include "osd_cull/error.h"

#include <algorithm>
#include <limits>

namespace osd_cull::plan {

const char* toString(Accuracy accuracy) {
  switch (accuracy) {
    case Accuracy::Bound:
      return "bound";
    case Accuracy::Listed:
      return "listed";
    case Accuracy::Surface:
      return "surface";
  }
  return "?";
}

std::string StageChoice::describe() const {
  if (!any()) return "none";
  std::string text;
  auto add = [&](const std::string& part) { text += (text.empty() ? "" : " + ") + part; };
  if (frustum) add("frustum");
  if (!backPatch.empty())
    add(backPatch + (accuracy == Accuracy::Bound ? "" : std::string("/") + toString(accuracy)));
  if (!occlusion.empty())
    add(occlusion + (aggressive ? " (aggressive, " : " (two-pass, ") + (hizFull ? "full" : "half") +
        (hizTight ? ", tight)" : ")"));
  return text;
}

uint64_t hizPixels(uint64_t pixels, bool fullResolution) {
  return fullResolution ? pixels : std::max<uint64_t>(1, pixels / 4);
}

namespace {

// The draw cost per patch of `c`'s mix of patch types, displaced or not, from `perBezier`.
double perPatch(const Calibration& calibration, const CostCase& c, double perBezier) {
  const double n = c.patches();
  if (n == 0) return 0.0;
  const double weight = (c.bezier + calibration.gregoryDrawFactor * c.gregory) / n;
  return weight * perBezier * (c.displaced ? calibration.displacedDrawFactorAt(c.tess) : 1.0);
}

}  // namespace

double drawMsPerPatch(const Calibration& calibration, const CostCase& c) {
  return perPatch(calibration, c, calibration.drawMs(c.tess));
}

double backDrawMsPerPatch(const Calibration& calibration, const CostCase& c) {
  return perPatch(calibration, c, calibration.backDrawMs(c.tess));
}

double cullMsPerPatch(const Calibration& calibration, const StageChoice& stages, double tess,
                      const CullRates& rates) {
  double ct = 0.0;
  // A back-patch or occlusion stage's calibrated cost is what it adds to a frustum kernel,
  // so a kernel without the frustum stage still pays for the kernel itself.
  if (stages.any()) ct += calibration.cullMs("frustum");
  if (!stages.backPatch.empty()) {
    if (stages.accuracy == Accuracy::Surface) {
      const auto it = calibration.surfaceCullMsPerPatch.find(stages.backPatch);
      if (it == calibration.surfaceCullMsPerPatch.end())
        throw Error("calibration: no surface-exact cull cost measured for back-patch method '" +
                    stages.backPatch + "' (run `osd-cull calibrate --force` with this library)");
      ct += it->second;
    } else {
      ct += calibration.cullMs(stages.backPatch);
      // The listed test runs after the bound, on the patches it keeps where the surface
      // faces away (§ "listed triangles" of docs/algorithms/drawn-triangles.md): its cost
      // per patch it runs on, times their share, adds to the bound kernel's.
      if (stages.accuracy == Accuracy::Listed)
        ct += rates.listedRuns * calibration.listedCullMs(stages.backPatch, tess);
    }
  }
  if (!stages.occlusion.empty()) {
    ct += calibration.cullMs(stages.occlusion);
    if (stages.hizTight) {
      if (!calibration.hizTightMsPerPatch)
        throw Error(
            "calibration: no tight Hi-Z lookup cost measured (run `osd-cull calibrate "
            "--force` with this library)");
      ct += *calibration.hizTightMsPerPatch;
    }
  }
  return ct;
}

Prediction predict(const Calibration& calibration, const CostCase& c, const StageChoice& stages,
                   const CullRates& rates) {
  Prediction p;
  const double n = c.patches();
  const double rt = drawMsPerPatch(calibration, c);
  const double rt0 = c.tessFactorZero ? calibration.drawZeroMsPerPatch : 0.0;
  const double rtBack = std::min(rt, backDrawMsPerPatch(calibration, c));
  double facingAway = 0.0, hidden = 0.0;  // culled by frustum or back-patch; by occlusion
  if (stages.frustum) facingAway += rates.frustum;
  if (!stages.backPatch.empty()) facingAway += rates.backPatch;
  if (!stages.occlusion.empty()) hidden += rates.occlusion;
  if (facingAway + hidden > 1.0) {  // shares of one set of patches: at most all of them
    const double scale = 1.0 / (facingAway + hidden);
    facingAway *= scale;
    hidden *= scale;
  }
  p.culled = facingAway + hidden;
  p.fixedMs = calibration.submitMs;
  if (stages.any()) {
    // Zachmann: T = t + (1 - P)·R, with the factor-0 draws of the culled patches (§5).
    p.cullMs = n * cullMsPerPatch(calibration, stages, c.tess, rates) + calibration.cullDispatchMs;
    p.drawMs = std::max(0.0, n * rt - facingAway * n * (rtBack - rt0) - hidden * n * (rt - rt0));
  } else {
    p.drawMs = n * rt;
  }
  if (!stages.occlusion.empty()) {
    p.hizMs = calibration.hizBuildMs(hizPixels(c.pixels, stages.hizFull)) +
              (stages.aggressive ? 0.0 : calibration.submitMs);
    // §6.3: with factor-0 draws the other pass draws every patch again at factor 0.
    if (!stages.aggressive) p.drawMs += n * rt0;
  }
  if (c.pointUpdate)
    p.updateMs = n * (c.gpuPointUpdate ? calibration.pointUpdateGpuMsPerPatch
                                       : calibration.pointUpdateCpuMsPerPatch);
  if (c.boundsPass) p.updateMs += n * calibration.boundsMs(c.boundsMethod);
  return p;
}

double breakEvenRate(double rt, double rt0, double ct) {
  if (rt <= rt0) return std::numeric_limits<double>::infinity();
  return (rt0 + ct) / (rt - rt0);
}

}  // namespace osd_cull::plan
