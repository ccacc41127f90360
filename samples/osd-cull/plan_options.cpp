#include "plan_options.h"

#include "option_checks.h"

#include "osd_cull/error.h"
#include "osd_cull/measure/calibrate.h"
#include "osd_cull/plan/calibration.h"
#include "osd_cull/vk/context.h"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <ostream>

namespace osd_cull::cli {

void addPlanAccuracyOption(CLI::App& app, std::string& accuracy) {
  app.add_option("--plan-accuracy", accuracy,
                 "the back-patch accuracy the plan may choose: auto (default: the\n"
                 "drawn-triangle bound or the listed triangles, whichever is predicted\n"
                 "cheaper; both conservative for the drawn triangles), bound, listed, or\n"
                 "surface (the papers' surface-exact test: can lose silhouette pixels)")
      ->type_name("MODE")
      ->check(oneOf({"auto", "bound", "listed", "surface"}))
      ->group("Culling");
}

void addPlanOptions(CLI::App& app, PlanArgs& args) {
  app.add_option("--plan", args.mode,
                 "auto: the effect plan chooses the cull stages each frame from this\n"
                 "device's calibration (`osd-cull calibrate`) and the rates it measures,\n"
                 "printing the plan when it changes (default; an explicit --cull or\n"
                 "--plan off fixes the choice)")
      ->type_name("MODE")
      ->check(oneOf({"auto", "off"}))
      ->group("Culling");
  app.add_option("--plan-calibration", args.calibration,
                 "plan with this calibration file instead of the device's cached one")
      ->type_name("FILE.txt")
      ->group("Culling");
  addPlanAccuracyOption(app, args.accuracy);
}

std::string missingCalibration(const PlanArgs& args, vulkan::Context& context) {
  if (!args.calibration.empty()) return "";
  const plan::CalibrationKey key = measure::calibrationKey(context);
  std::string outdated;
  if (plan::loadCachedCalibration(key, &outdated)) return "";
  const std::string why = outdated.empty() ? "no calibration of this device cached" : outdated;
  // With a cache to keep it in, the first planned render measures a quick calibration
  // (under 30 s, measure/calibrate.h) instead of giving up the plan: a user who never ran
  // `osd-cull calibrate` still gets culling that pays. Without a cache
  // (OSD_CULL_CALIBRATION_CACHE=off, as in the tests) it would be measured on every run.
  if (plan::calibrationCacheDirectory().empty())
    return why + " (the calibration cache is off): run `osd-cull calibrate --quick`, or give " +
           "--plan-calibration FILE";
  const std::filesystem::path file = plan::calibrationCacheFile(key);
  std::cerr << "plan: " << why << "; measuring a quick calibration of this device (under 30 s, "
            << "kept in " << file.string() << "; `osd-cull calibrate` measures the full one)\n";
  measure::CalibrateOptions o;
  o.quick = true;
  o.progress = [](const std::string& line) { std::cerr << "calibrate: " << line << "\n"; };
  plan::storeCalibration(measure::calibrate(context, o), file);
  return "";
}

std::unique_ptr<plan::Planner> makePlanner(const PlanArgs& args, vulkan::Context& context,
                                           bool cullGiven, const std::string& backPatchMethod,
                                           std::ostream& out) {
  if (args.mode == "off") {
    out << "plan: off (--plan off)\n";
    return nullptr;
  }
  if (cullGiven) {
    out << "plan: off (--cull given: a fixed choice)\n";
    return nullptr;
  }
  if (const std::string missing = missingCalibration(args, context); !missing.empty()) {
    out << "plan: off, drawing without culling (" << missing << ")\n";
    return nullptr;
  }
  const plan::Calibration calibration = measure::deviceCalibration(context, args.calibration);
  out << "plan: auto, calibration of " << calibration.key.device
      << (calibration.quick ? " (quick)" : "") << "\n";
  plan::PlannerOptions options;
  options.accuracy = args.accuracy;
  if (!backPatchMethod.empty()) {
    options.backPatchMethods = {backPatchMethod};
    out << "plan: back-patch method restricted to " << backPatchMethod << " (--backpatch-method)\n";
  }
  return std::make_unique<plan::Planner>(calibration, options);
}

void printPlanChange(const plan::Plan* last, const plan::Plan& p, std::ostream& out,
                     const std::string& who, bool verbose) {
  char line[160];
  std::snprintf(line, sizeof line,
                ", frame %llu: %s%s (predicted %.2f ms, without culling %.2f ms)\n",
                static_cast<unsigned long long>(p.frame), p.stages.describe().c_str(),
                p.probe ? " [re-probe]" : "", p.predicted.totalMs(), p.predictedUnculled.totalMs());
  out << (who.empty() ? "plan" : "plan of " + who) << line;
  if (!verbose) return;
  if (last) {
    std::string changes = plan::planChange(*last, p);
    for (size_t start = 0; start < changes.size();) {
      const size_t end = changes.find('\n', start);
      out << "  " << changes.substr(start, end - start) << "\n";
      start = end + 1;
    }
    return;
  }
  for (const auto& [kind, e] : p.effects())
    out << "  " << plan::toString(kind) << " " << (e->on ? "on" : "off")
        << (e->choice.empty() ? "" : " (" + e->choice + ")") << ": " << e->reason << "\n";
}

}  // namespace osd_cull::cli
