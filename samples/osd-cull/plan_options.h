#pragma once
/// \file plan_options.h
/// \brief `--plan auto|off` and `--plan-calibration FILE` of `osd-cull render`, and the
/// planner they make (osd_cull/plan/planner.h).

#include "command.h"

#include "osd_cull/plan/planner.h"

#include <iosfwd>
#include <memory>
#include <string>

namespace osd_cull::vulkan {
class Context;
}

namespace osd_cull::cli {

/// \brief The plan options as given.
struct PlanArgs {
  std::string mode = "auto";      ///< auto or off
  std::string calibration;        ///< a calibration file instead of the device's cached one
  std::string accuracy = "auto";  ///< plan::PlannerOptions::accuracy
};

/// \brief Declares `--plan-accuracy auto|bound|listed|surface` (plan::PlannerOptions::
/// accuracy) in the "Culling" group.
void addPlanAccuracyOption(CLI::App& app, std::string& accuracy);

/// \brief Declares `--plan MODE`, `--plan-calibration FILE` and `--plan-accuracy` in the
/// "Culling" group.
void addPlanOptions(CLI::App& app, PlanArgs& args);

/// \brief Why there is no calibration to plan with ("" when there is one): no
/// --plan-calibration and no (current, valid) calibration of this device in the cache. With
/// the cache on, a missing, outdated or damaged calibration is measured (`calibrate
/// --quick`, progress on stderr) and stored instead, and the answer is "". Every command
/// that plans (render, plan) finds its calibration through this, so all treat a
/// cache file alike.
std::string missingCalibration(const PlanArgs& args, vulkan::Context& context);

/// \brief The planner of a render, or null when the plan is off, with one line to `out`
/// saying which and why: `--plan off`, an explicit `--cull` (a fixed choice), or no
/// calibration of this device. `backPatchMethod` (non-empty: --backpatch-method given)
/// restricts the plan to that method (PlannerOptions::backPatchMethods), and says so.
/// \throws osd_cull::Error for a --plan-calibration file that does not load.
std::unique_ptr<plan::Planner> makePlanner(const PlanArgs& args, vulkan::Context& context,
                                           bool cullGiven, const std::string& backPatchMethod,
                                           std::ostream& out);

/// \brief Prints a plan that differs from `last` (every effect when `last` is null):
/// `plan, frame F: STAGES (predicted X ms, without culling Y ms)` and its changed effects;
/// with `who` (a scene's "instance 'NAME' in view 'VIEW'"): `plan of WHO, frame F: ...`.
/// Without `verbose` (render's default) the headline line alone.
void printPlanChange(const plan::Plan* last, const plan::Plan& plan, std::ostream& out,
                     const std::string& who = "", bool verbose = true);

}  // namespace osd_cull::cli
