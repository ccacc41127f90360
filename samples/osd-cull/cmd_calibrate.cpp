// osd-cull calibrate: measures what the effect plan's cost model needs on this device
// (osd_cull/measure/calibrate.h) and caches it, keyed by device, driver and library version.
#include "command.h"
#include "device_options.h"
#include "option_checks.h"

#include "osd_cull/measure/calibrate.h"
#include "osd_cull/plan/cost_model.h"
#include "osd_cull/vk/context.h"

#include <cstdio>
#include <iostream>
#include <memory>

namespace osd_cull::cli {
namespace {

const char* kDescription =
    R"(Measures on this device the terms of the effect plan's cost model (Niessner & Loop
§6.3, Zachmann's T = t + (1 - P)R): draw cost per patch against tessellation level RT(tf)
with its exact TES work, a patch drawn with factor 0 (RT0), each cull stage's cost per
patch (CT: frustum, every back-patch method, Hi-Z occlusion and the six displaced kernels),
the displaced draw against the undisplaced one (a built-in torus with texture coordinates
and a procedural map), the Hi-Z build at two image sizes and at full resolution, the tight
Hi-Z lookup against the paper's, the CPU and GPU control-point
update and the bounds pass per patch and method, the surface-exact back-patch kernels and
the listed-triangle test against the tessellation level; medians over repeats. Stored in the calibration cache ($OSD_CULL_CALIBRATION_CACHE, else
$XDG_CACHE_HOME/osd_cull/calibration or ~/.cache/osd_cull/calibration) under the device,
driver and library version; `osd-cull plan` and `render --plan auto` read it there. A
cached calibration is shown, not measured again, unless --force is given.)";

struct CalibrateArgs {
  bool quick = false;
  bool force = false;
  std::string out;
  uint32_t repeats = 0;
  vulkan::ContextOptions device;
};

void print(const plan::Calibration& c) {
  std::printf("device: %s; driver: %s; osd_cull %s%s, %u patches, medians of %u\n",
              c.key.device.c_str(), c.key.driver.c_str(), c.key.library.c_str(),
              c.quick ? " (quick)" : "", c.patches, c.repeats);
  std::printf("fixed frame cost (clear, submit, wait): %.3f ms; cull dispatch %.3f ms\n",
              c.submitMs, c.cullDispatchMs);
  std::printf("RT0 (factor-0 patch): %.3f us; Gregory patches draw %.2fx a Bezier patch\n",
              1e3 * c.drawZeroMsPerPatch, c.gregoryDrawFactor);
  std::printf("\n| tess | RT us/patch | RT back-facing us/patch | TES/patch |");
  for (const auto& [stage, ms] : c.cullMsPerPatch)
    if (stage != "frustum") std::printf(" break-even %s |", stage.c_str());
  std::printf("\n|---:|---:|---:|---:|");
  for (size_t i = 1; i < c.cullMsPerPatch.size(); ++i) std::printf("---:|");
  std::printf("\n");
  for (const plan::DrawCost& d : c.draw) {
    std::printf("| %u | %.3f | %.3f | %.0f |", d.tess, 1e3 * d.msPerPatch, 1e3 * d.backMsPerPatch,
                d.tesPerPatch);
    for (const auto& [stage, ms] : c.cullMsPerPatch)
      if (stage != "frustum") {
        // A back-patch cull saves a back-facing patch's draw, an occlusion cull a shaded one.
        const double saved = stage == "hiz" ? d.msPerPatch : d.backMsPerPatch;
        const double x = plan::breakEvenRate(saved, 0.0, ms + c.cullMs("frustum"));
        if (x > 1.0)
          std::printf(" never |");
        else
          std::printf(" %.1f%% |", 100.0 * x);
      }
    std::printf("\n");
  }
  std::printf("\nCT per stage (us/patch; back-patch and occlusion on top of frustum):");
  for (const auto& [stage, ms] : c.cullMsPerPatch)
    std::printf(" %s %.3f;", stage.c_str(), 1e3 * ms);
  std::printf("\nHi-Z build:");
  for (const plan::SizeCost& h : c.hizBuild)
    std::printf(" %llu px level 0: %.2f ms;", static_cast<unsigned long long>(h.pixels), h.ms);
  if (c.hizTightMsPerPatch)
    std::printf(" tight lookup over the paper's: %.3f us/patch;", 1e3 * *c.hizTightMsPerPatch);
  std::printf("\npoint update per patch: cpu %.3f us, gpu %.3f us; bounds pass %.3f us\n",
              1e3 * c.pointUpdateCpuMsPerPatch, 1e3 * c.pointUpdateGpuMsPerPatch,
              1e3 * c.boundsMsPerPatch);
  if (!c.displacedDrawFactor.empty()) {
    std::printf("displaced draw RT(tf) / undisplaced (procedural map on the UV torus):");
    for (const auto& [level, factor] : c.displacedDrawFactor)
      std::printf(" tess %u %.2fx;", level, factor);
    std::printf("\n");
  }
  if (!c.boundsMsPerMethod.empty()) {
    std::printf("bounds pass per patch and method:");
    for (const auto& [method, ms] : c.boundsMsPerMethod)
      std::printf(" %s %.3f us;", method.c_str(), 1e3 * ms);
    std::printf("\n");
  }
  if (!c.surfaceCullMsPerPatch.empty()) {
    std::printf("surface-exact back-patch CT (us/patch, on top of frustum):");
    for (const auto& [method, ms] : c.surfaceCullMsPerPatch)
      std::printf(" %s %.3f;", method.c_str(), 1e3 * ms);
    std::printf("\n");
  }
  for (const auto& [method, levels] : c.listedCullMsPerPatch) {
    std::printf("listed-triangle test of %s on top of its bound (us per patch it runs on):",
                method.c_str());
    for (const auto& [level, ms] : levels) std::printf(" tess %u %.3f;", level, 1e3 * ms);
    std::printf("\n");
  }
  std::printf(
      "(break-even x = (RT0 + CT) / (RT - RT0), Niessner & Loop §6.3, with RT0 = 0 for "
      "compact draw lists and CT including the frustum kernel)\n");
}

int run(const CalibrateArgs& args) {
  if (!args.out.empty()) checkOutputFile(args.out, "--out", {".txt"});
  vulkan::Context context(args.device);
  const plan::CalibrationKey key = measure::calibrationKey(context);
  const std::filesystem::path cacheFile = plan::calibrationCacheFile(key);
  std::optional<plan::Calibration> c;
  std::string outdated;
  if (!args.force) c = plan::loadCachedCalibration(key, &outdated);
  if (!outdated.empty()) std::cout << "note: " << outdated << "; measuring it again\n";
  if (c && (!args.quick || c->quick)) {
    std::cout << "cached calibration: " << cacheFile.string() << " (--force measures again)\n";
  } else {
    measure::CalibrateOptions o;
    o.quick = args.quick;
    o.repeats = args.repeats;
    o.progress = [](const std::string& line) { std::cerr << "calibrate: " << line << "\n"; };
    c = measure::calibrate(context, o);
    if (!cacheFile.empty()) {
      plan::storeCalibration(*c, cacheFile);
      std::cout << "wrote " << cacheFile.string() << "\n";
    }
  }
  if (!args.out.empty()) {
    plan::storeCalibration(*c, args.out);
    std::cout << "wrote " << args.out << "\n";
  }
  print(*c);
  return 0;
}

Runner setup(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  app.add_flag("--quick", args->quick,
               "a smaller mesh at 640x360 and 3 repeats (under 30 s on lavapipe)");
  app.add_flag("--force", args->force, "measure even when a calibration is cached");
  app.add_option("--out", args->out, "also write the calibration to this file")
      ->type_name("FILE.txt");
  app.add_option("--repeats", args->repeats, "repeats per median (default 3 quick, 7 full)")
      ->type_name("N")
      ->check(integerIn(1, 1000));
  addDeviceOptions(app, args->device);
  return [args] { return run(*args); };
}

const Registration kRegistration({"calibrate",
                                  "measure this device's costs for the effect plan (cached)",
                                  kDescription, setup});

}  // namespace
}  // namespace osd_cull::cli
