// `osd-cull verify`: runs each cull method on many random views of a mesh and checks it
// against the double-precision CPU reference, the visibility oracle and (optionally) dense
// sampling and the image; prints a table and writes JSON.
#include "command.h"
#include "device_options.h"
#include "displacement_args.h"
#include "mesh_patches.h"
#include "option_checks.h"
#include "scene_source.h"
#include "scene_verify.h"
#include "verify_args.h"
#include "verify_report.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass_displaced.h"
#include "osd_cull/frame/verify/cull_verification.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/patch/face_varying_uv.h"
#include "osd_cull/vk/context.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

namespace osd_cull::cli {
namespace {

const char* kDescription =
    R"(Runs each cull method alone (the frustum test, each back-patch method, the Hi-Z occlusion
test against the pyramid of the full draw's depth) on random views of MESH (default: the
built-in mesh) and checks every view: GPU culls must be culls of the
double-precision CPU reference, culled patches must have no pixel in the visibility oracle
(item buffer of the unculled draw), and optionally no visible sample on a dense sampling of
the patch and no pixel lost in the image drawn from the survivors. Prints a table (progress
on stderr) and optionally writes JSON.)";

const char* kFooter =
    R"(Views (both keep the whole bounding sphere, centre of the bounding box and radius half its
diagonal, inside the view, with a random roll):
  sphere        eye uniformly distributed on the sphere of radius r / sin(fov/2) around the
                centre (2.92 r for 40 degrees), looking at the centre (back-patch paper)
  whole-object  random direction, distance in [1, 2] times that radius, view direction
                turned off-centre as far as the object stays in view (occlusion paper))";

/// \brief Every registered cull method, frustum first, then back-patch, then occlusion.
std::vector<std::string> allMethods() {
  std::vector<std::string> methods;
  for (auto stage :
       {frame::CullStage::Frustum, frame::CullStage::BackPatch, frame::CullStage::Occlusion})
    for (const auto& m : frame::cullMethodNames(stage))
      if (!frame::cullMethod(m).displaced) methods.push_back(m);  // those run with --displacement
  return methods;
}

/// \brief The mesh form's usage checks that need no mesh: --frames, the view set, the
/// number of views, the oracle against the image check.
/// \throws UsageError (or the view set's error) naming the option.
void checkMeshForm(const VerifyArgs& args) {
  if (args.frames) throw UsageError("--frames applies to the scene form (verify SCENE)");
  (void)frame::parseViewSet(args.viewSet);  // throws on an unknown set
  if (args.views.value_or(100) == 0)
    throw UsageError("--views: the mesh form needs at least 1 view");
  if (args.imageCheck && args.noOracle)
    throw UsageError("--image-check compares with the oracle's draw; drop --no-oracle");
}

/// \brief The methods to verify: --methods, else every registered method and the
/// displaced kernels --displaced-bound and --displaced-box choose.
std::vector<std::string> verifiedMethods(const VerifyArgs& args,
                                         const DisplacementChoice& displacement) {
  std::vector<std::string> methods = args.methods.empty() ? allMethods() : splitList(args.methods);
  if (args.methods.empty())
    for (const std::string& name : kernelNames(displacement)) methods.push_back(name);
  return methods;
}

/// \brief The verifier's options from the command line: tessellation (uniform or
/// adaptive), oracle, reference stride, sampling, image check, back-patch test, Hi-Z and
/// the displacement map when given.
frame::VerifyOptions verifyOptions(const VerifyArgs& args, const vulkan::Context& context,
                                   const MeshPatches& mesh,
                                   const std::optional<bound::DisplacementMap>& displacementMap,
                                   const DisplacementChoice& displacement) {
  frame::VerifyOptions options;
  options.tessellation.uniformLevel = args.tess;
  if (args.adaptive > 0.0) {
    // The oracle, the image check and the cull kernel all read the levels pass's levels.
    options.tessellation.mode = frame::TessellationOptions::Mode::Adaptive;
    options.tessellation.pixelsPerSegment = args.adaptive;
  }
  options.tessellation.maxLevel = context.info().limits.maxTessellationGenerationLevel;
  options.oracle = !args.noOracle;
  options.referenceStride = args.referenceEvery;
  options.samplingGrid = args.sample;
  options.imageCheck = args.imageCheck;
  options.drawnTriangles = !args.surfaceExact;
  options.drawnEnumerate = args.drawnEnumerate;
  options.clusters = args.clusters;
  options.hiz.fullResolution = args.hizFull;
  options.hiz.lookup = args.hizTight ? bound::HiZLookup::Tight : bound::HiZLookup::Paper;
  if (displacementMap) {
    options.displacementMap = &*displacementMap;
    options.uvCorners = mesh.uvCorners;
    options.countCracks = true;  // UV seams open the displaced surface: report them
    options.tessellation.displaced = displacement.tessellation;
  }
  return options;
}

/// \brief The random views of the mesh (--view-set, --views, --seed, size, fov).
std::vector<frame::Camera> verifiedViews(const VerifyArgs& args, const PatchSet& patches) {
  frame::ViewSetOptions viewOptions;
  viewOptions.set = frame::parseViewSet(args.viewSet);
  viewOptions.count = args.views.value_or(100);
  viewOptions.seed = args.seed;
  viewOptions.width = args.width.value_or(256);
  viewOptions.height = args.height.value_or(256);
  viewOptions.fovyDegrees = args.fov;
  return frame::randomViews(frame::boundsOf(patches.points), viewOptions);
}

/// \brief The lines before the table: the mesh, the views, the displacement, the
/// back-patch test, the oracle's back faces and the methods skipped.
void printVerifyHeader(const VerifyArgs& args, const MeshPatches& mesh,
                       const vulkan::Context& context,
                       const std::optional<bound::DisplacementMap>& displacementMap,
                       const frame::CullVerifier& verifier) {
  const PatchSet& patches = mesh.patches;
  std::printf("mesh: %s, %u patches (%u Bezier + %u Gregory), level %d\n", mesh.name.c_str(),
              patches.patchCount(), patches.bezierCount, patches.gregoryCount,
              args.patchOptions.isolationLevel);
  for (const std::string& note : mesh.notes) std::printf("note: %s\n", note.c_str());
  const std::string tessText = args.adaptive > 0.0
                                   ? "adaptive " + std::to_string(args.adaptive) + " px/segment"
                                   : "tess " + std::to_string(args.tess);
  std::printf("views: %u %s (seed %llu), %ux%u, fov %.1f, %s, device %s\n",
              args.views.value_or(100), frame::toString(frame::parseViewSet(args.viewSet)),
              static_cast<unsigned long long>(args.seed), args.width.value_or(256),
              args.height.value_or(256), args.fov, tessText.c_str(), context.info().name.c_str());
  if (displacementMap) {
    const bound::DisplacementRange r = displacementMap->displacementRange();
    std::printf(
        "displacement: %s, %ux%u, scale %g, midlevel %g, D in [%g, %g], lod %u; "
        "back-patch culling off (below)\n",
        displacementMap->name().c_str(), displacementMap->width(), displacementMap->height(),
        displacementMap->scale(), displacementMap->midlevel(), r.dmin, r.dmax,
        displacementMap->maxLod());
  }
  std::printf("back-patch culling: %s (%s)%s\n", mesh.backPatch.enabled ? "on" : "off",
              mesh.backPatch.reason.c_str(),
              args.surfaceExact     ? ", surface-exact"
              : args.drawnEnumerate ? ", conservative for the drawn triangles (listed)"
                                    : ", conservative for the drawn triangles");
  std::printf("oracle and image draws: back-facing triangles %s\n",
              verifier.cullBackFaces() ? "culled (closed mesh)" : "drawn");
  printSkipped(verifier.skipped(), mesh.backPatch.reason);
  std::fflush(stdout);
}

/// \brief Verifies every view, with progress on stderr about every twentieth.
void verifyViews(frame::CullVerifier& verifier, const std::vector<frame::Camera>& cameras) {
  const uint32_t views = uint32_t(cameras.size());
  const auto start = std::chrono::steady_clock::now();
  const uint32_t step = std::max(1u, views / 20);
  for (uint32_t v = 0; v < views; ++v) {
    verifier.verifyView(cameras[v]);
    if ((v + 1) % step == 0 || v + 1 == views) {
      const double s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(stderr, "verify: %u/%u views, %.1f s\n", v + 1, views, s);
    }
  }
}

/// \brief The line on the cracks a displaced surface opens at UV seams (when counted).
void printCracks(const frame::CrackTotals& cracks, const MeshPatches& mesh) {
  if (cracks.views == 0) return;
  std::printf(
      "cracks (displaced surface open at UV seams, back faces culled): %llu pixels "
      "over %llu views, %llu views with cracks, at most %llu in one view; %u UV seam "
      "edges\n",
      static_cast<unsigned long long>(cracks.pixels), static_cast<unsigned long long>(cracks.views),
      static_cast<unsigned long long>(cracks.viewsWithCracks),
      static_cast<unsigned long long>(cracks.worstView),
      countUVSeamEdges(mesh.patches, mesh.uvCorners));
}

/// \brief Writes the run's settings, the per-method totals, cracks, skipped methods and
/// the verdict to --json.
/// \throws osd_cull::Error when the file cannot be written.
void writeVerifyJson(const VerifyArgs& args, const MeshPatches& mesh,
                     const vulkan::Context& context, const frame::CullVerifier& verifier,
                     bool oracle, const VerifyVerdict& verdict) {
  const PatchSet& patches = mesh.patches;
  nlohmann::ordered_json out;
  out["mesh"] = mesh.name;
  out["patches"] = patches.patchCount();
  out["bezier_patches"] = patches.bezierCount;
  out["gregory_patches"] = patches.gregoryCount;
  out["level"] = args.patchOptions.isolationLevel;
  out["views"] = args.views.value_or(100);
  out["view_set"] = frame::toString(frame::parseViewSet(args.viewSet));
  out["seed"] = args.seed;
  out["width"] = args.width.value_or(256);
  out["height"] = args.height.value_or(256);
  out["fov"] = args.fov;
  out["tess"] = args.tess;
  out["adaptive_pixels"] = args.adaptive;
  out["device"] = context.info().name;
  out["back_patch"] = {{"enabled", mesh.backPatch.enabled},
                       {"reason", mesh.backPatch.reason},
                       {"drawn_triangles", !args.surfaceExact},
                       {"drawn_enumerate", args.drawnEnumerate},
                       {"oracle_culls_back_faces", verifier.cullBackFaces()}};
  out["methods"] = nlohmann::ordered_json::array();
  for (const auto& t : verifier.totals())
    out["methods"].push_back(methodJson(t, patches.patchCount(), oracle));
  const frame::CrackTotals& cracks = verifier.cracks();
  if (cracks.views > 0)
    out["cracks"] = {{"views", cracks.views},
                     {"pixels", cracks.pixels},
                     {"views_with_cracks", cracks.viewsWithCracks},
                     {"worst_view", cracks.worstView}};
  finishVerifyJson(std::move(out), verifier.skipped(), verdict, args.json);
}

int run(const VerifyArgs& args) {
  if (args.source.path && isSceneArgument(*args.source.path)) {
    if (args.adaptive > 0.0) throw UsageError("--adaptive applies to the mesh form (verify MESH)");
    return verifyScene(args);
  }
  checkMeshForm(args);
  const DisplacementChoice displacement = displacementChoice(args.displacement, true);
  const std::vector<std::string> methods = verifiedMethods(args, displacement);
  if (!args.json.empty()) checkOutputFile(args.json, "--json", {".json"});

  MeshPatches mesh = meshPatches(loadMeshSource(args.source), args.patchOptions);
  // Displaced: no back-patch culling, and the oracle draws back faces too (the displaced
  // surface may fold; its holes at UV seams show the inside).
  if (displacement.map) mesh.backPatch = {false, frame::kDisplacedBackPatchNote};
  std::optional<bound::DisplacementMap> displacementMap;
  if (displacement.map) displacementMap.emplace(adapters::loadDisplacementMap(*displacement.map));
  vulkan::Context context(args.device);
  const frame::VerifyOptions options =
      verifyOptions(args, context, mesh, displacementMap, displacement);
  frame::CullVerifier verifier(context, mesh.patches, methods, mesh.backPatch, options);
  const std::vector<frame::Camera> cameras = verifiedViews(args, mesh.patches);

  printVerifyHeader(args, mesh, context, displacementMap, verifier);
  verifyViews(verifier, cameras);
  printCracks(verifier.cracks(), mesh);
  const VerifyVerdict verdict =
      printVerifyTables(verifier.totals(), mesh.patches.patchCount(), options.oracle,
                        args.surfaceExact, args.sample > 0 || args.imageCheck);
  if (!args.json.empty()) writeVerifyJson(args, mesh, context, verifier, options.oracle, verdict);
  const vulkan::ValidationLog* log = context.validationLog();
  return finishVerify(verdict, log ? log->count() : 0);
}

Runner setup(CLI::App& app) {
  auto args = std::make_shared<VerifyArgs>();
  addMeshOptions(app, args->source);
  addPatchOptions(app, args->patchOptions);
  addOptional(app, "--views", args->views,
              "number of views (default 100; a scene: random views per frame, default 4)")
      ->type_name("N")
      ->check(integerIn(0, 10'000'000));
  addOptional(app, "--frames", args->frames, "a scene: frames from its frameStart (default 2)")
      ->type_name("N")
      ->check(integerIn(1, 100000));
  app.add_option("--seed", args->seed, "random seed of the views (default 1)")
      ->type_name("S")
      ->check(integerIn(0, 1L << 62));
  app.add_option("--view-set", args->viewSet, "sphere or whole-object (default sphere)")
      ->type_name("SET")
      ->check(oneOf({"sphere", "whole-object"}));
  app.add_option("--methods", args->methods,
                 "methods to run (default: every registered method: frustum,\n"
                 "back-patch and occlusion (hiz); back-patch methods are skipped with\n"
                 "the reason when the mesh is not a closed, outward-oriented solid, hiz\n"
                 "without the oracle; a scene: frustum, tcone, ncone, tangent-plane)")
      ->type_name("A,B,...")
      ->check(listOf(allMethods()));
  app.add_flag("--hiz-full", args->hizFull,
               "Hi-Z top level at full resolution (default: half, as the paper)");
  app.add_flag("--hiz-tight", args->hizTight,
               "Hi-Z lookup one level finer where 2x2 texels still cover the box");
  app.add_option("--tess", args->tess, "uniform tessellation level of the oracle draws (default 4)")
      ->type_name("N")
      ->check(integerIn(1, 64));
  app.add_option("--adaptive", args->adaptive,
                 "screen-space adaptive tessellation of every draw (oracle, image check,\n"
                 "cull kernel: the same precomputed levels), PIXELS per segment; the mesh form")
      ->type_name("PIXELS")
      ->check(numberIn(0.01, 1e6));
  addSizeOptions(app, args->width, args->height, 1, "256 x 256; a scene: 128 x 128");
  app.add_option("--fov", args->fov, "vertical field of view in degrees (default 40)")
      ->type_name("DEG")
      ->check(numberIn(1.0, 170.0));
  app.add_option("--reference-every", args->referenceEvery,
                 "compare with the CPU reference on every K-th view (default 1;\n"
                 "0: never)")
      ->type_name("K")
      ->check(integerIn(0, 1'000'000));
  app.add_flag("--no-oracle", args->noOracle,
               "skip the oracle (no false-cull or oracle-rate figures)");
  app.add_option("--sample", args->sample,
                 "check culled patches on an (N+1) x (N+1) sampling grid (default 0:\n"
                 "off)")
      ->type_name("N")
      ->check(integerIn(0, 256));
  app.add_flag("--image-check", args->imageCheck,
               "draw the survivors of each method and compare with the full draw");
  app.add_flag("--surface-exact", args->surfaceExact,
               "back-patch tests exact for the surface only, as the papers measure\n"
               "them (default: also conservative for the drawn chord triangles,\n"
               "docs/algorithms/drawn-triangles.md); such culls can take single\n"
               "silhouette pixels, which are then reported but do not fail the run");
  auto* enumerate =
      app.add_flag("--drawn-enumerate", args->drawnEnumerate,
                   "with uniform tessellation, cull a patch the drawn-triangle bound keeps when\n"
                   "every triangle the tessellator can draw for it faces away (tested in the\n"
                   "kernel; docs/algorithms/drawn-triangles.md, \"Enumerated triangles\")");
  enumerate->excludes("--surface-exact");
  app.add_flag("--clusters", args->clusters,
               "run frustum, tcone and ncone with clusters tested first\n"
               "(docs/algorithms/clusters.md)");
  app.add_option("--json", args->json, "write the results as JSON")->type_name("FILE.json");
  addDeviceOptions(app, args->device);
  addDisplacementOptions(app, args->displacement, true);
  return [args] { return run(*args); };
}

const Registration kRegistration(
    {"verify", "check every cull method against the CPU reference and the oracle on random views",
     kDescription, setup, std::string(kFooter) + "\n" + kSceneVerifyUsage});

}  // namespace
}  // namespace osd_cull::cli
