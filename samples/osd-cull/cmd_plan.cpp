// osd-cull plan SCENE|MESH: prints the effect plan (osd_cull/plan/planner.h) of every
// instance in every view: each effect on or off, the choice, the reason and the predicted
// ms, from this device's calibration (`osd-cull calibrate`).
#include "command.h"
#include "device_options.h"
#include "mesh_patches.h"
#include "mesh_source.h"
#include "option_checks.h"
#include "plan_options.h"
#include "scene_source.h"

#include "osd_cull/error.h"
#include "osd_cull/measure/calibrate.h"
#include "osd_cull/plan/planner.h"
#include "osd_cull/plan/scene_inputs.h"
#include "osd_cull/vk/context.h"

#include <filesystem>
#include <iostream>
#include <memory>

namespace osd_cull::cli {
namespace {

const char* kDescription =
    R"(Prints the effect plan of SCENE (a scene file, an OBJ sequence, built-in:scene; the
default) or of MESH seen framed from the default direction: per instance and view which
cull stages run (frustum, which back-patch method and at which accuracy, Hi-Z occlusion), one or two passes, the
Hi-Z resolution, whether and where the control points are updated, the bounds pass and the
displacement kernel, each with its reason and the predicted change in ms, and the
predicted frame against no culling. The plan is made from this device's calibration
(`osd-cull calibrate`, or --calibration FILE) with prior cull rates: it is the first
frame's plan; while a scene plays (`render`) the rates are measured and the plan follows.)";

struct PlanCommandArgs {
  MeshSource source;
  PatchOptions patchOptions;
  uint32_t tess = 4;
  uint32_t frame = 0;
  std::optional<uint32_t> width, height;
  bool displaced = false;
  std::string calibration;
  std::string accuracy = "auto";
  vulkan::ContextOptions device;
};

std::vector<plan::ScenePlanInput> meshInputs(const PlanCommandArgs& args) {
  if (!std::filesystem::exists(*args.source.path))
    throw Error(*args.source.path + ": no such file");
  const LoadedMesh loaded = loadMeshSource(args.source);
  const MeshPatches mesh = meshPatches(loaded, args.patchOptions);
  for (const std::string& note : mesh.notes) std::cout << "note: " << note << "\n";
  plan::PlanInput in;
  in.mesh = std::filesystem::path(*args.source.path).filename().string();
  in.view = "default";
  in.bezier = mesh.patches.bezierCount;
  in.gregory = mesh.patches.gregoryCount;
  in.tess = args.tess;
  in.objectBounds = frame::boundsOf(mesh.patches.points);
  const glm::dvec3 up = loaded.bezier ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
  const glm::dvec3 from = loaded.bezier ? glm::dvec3(0.6, -1.0, 0.5) : glm::dvec3(0.45, 0.35, 1.0);
  in.camera = frame::frameBounds(in.objectBounds, from, up, 40.0, args.width.value_or(1280),
                                 args.height.value_or(720));
  in.backPatchValidity = mesh.backPatch;
  in.displaced = args.displaced;
  in.selfOccluding = plan::mayHideItself(mesh.patches);
  return {{"default/0", 0, 0, in}};
}

int run(const PlanCommandArgs& args) {
  const std::string argument = args.source.path.value_or("built-in:scene");
  const bool isScene = isSceneArgument(argument);
  if (args.displaced && isScene) throw UsageError("--displaced applies to a MESH, not to a scene");
  vulkan::Context context(args.device);
  // As render finds it (missingCalibration): an outdated or damaged cached calibration is
  // measured again, not refused here and re-measured there.
  PlanArgs planArgs;
  planArgs.calibration = args.calibration;
  if (const std::string missing = missingCalibration(planArgs, context); !missing.empty())
    throw Error("no calibration to plan with: " + missing);
  const plan::Calibration calibration = measure::deviceCalibration(context, args.calibration);
  std::vector<plan::ScenePlanInput> inputs;
  if (isScene) {
    scene::LoadedScene loaded = loadSceneArgument(argument, 0);
    if (args.width) loaded.description.settings.width = *args.width;
    if (args.height) loaded.description.settings.height = *args.height;
    inputs = plan::scenePlanInputs(loaded, args.frame, args.tess);
  } else {
    inputs = meshInputs(args);
  }
  std::cout << "plan of " << argument << " at frame " << args.frame << ", tess " << args.tess
            << ", calibration of " << calibration.key.device << " (" << calibration.key.driver
            << (calibration.quick ? ", quick" : "") << ")\n\n";
  plan::PlannerOptions options;
  options.accuracy = args.accuracy;
  plan::Planner planner(calibration, options);
  std::vector<plan::Plan> plans;
  for (const plan::ScenePlanInput& s : inputs)
    plans.push_back(planner.plan(s.key, s.input, args.frame));
  std::cout << plan::planTable(plans);
  double planned = 0, unculled = 0;
  for (const plan::Plan& p : plans) {
    planned += p.predicted.totalMs();
    unculled += p.predictedUnculled.totalMs();
  }
  std::printf(
      "\npredicted: %.2f ms planned against %.2f ms without culling (sum over %zu "
      "instance views)\n",
      planned, unculled, plans.size());
  return 0;
}

Runner setup(CLI::App& app) {
  auto args = std::make_shared<PlanCommandArgs>();
  addMeshOptions(app, args->source);
  addPatchOptions(app, args->patchOptions);
  addSizeOptions(app, args->width, args->height, 16, "the scene's, or 1280 x 720");
  app.add_option("--tess", args->tess, "uniform tessellation level (default 4)")
      ->type_name("N")
      ->check(integerIn(1, 64));
  app.add_option("--frame", args->frame, "the scene frame to plan (default 0)")
      ->type_name("N")
      ->check(integerIn(0, 10000000));
  app.add_flag("--displaced", args->displaced, "plan MESH as displaced (a displacement map bound)");
  app.add_option("--calibration", args->calibration,
                 "a calibration file instead of this device's cached one")
      ->type_name("FILE.txt");
  addPlanAccuracyOption(app, args->accuracy);
  addDeviceOptions(app, args->device);
  return [args] { return run(*args); };
}

const Registration kRegistration({"plan",
                                  "print the effect plan of a scene or mesh (what runs and why)",
                                  kDescription, setup});

}  // namespace
}  // namespace osd_cull::cli
