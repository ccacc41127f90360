// `osd-cull verify`: runs each cull method on many random views of a mesh and checks it
// against the double-precision CPU reference, the visibility oracle and (optionally) dense
// sampling and the image; prints a table and writes JSON.
#include "command.h"
#include "displacement_args.h"
#include "mesh_patches.h"
#include "scene_source.h"
#include "scene_verify.h"
#include "verify_report.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass_displaced.h"
#include "osd_cull/frame/verify/cull_verification.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/vk/context.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

namespace osd_cull::cli {
namespace {

const char* kUsage = R"(Usage: osd-cull verify [MESH] [options]

Runs each cull method alone (the frustum test, each back-patch method, the Hi-Z occlusion
test against the pyramid of the full draw's depth) on random views of MESH (default: the
built-in mesh) and checks every view: GPU culls must be culls of the
double-precision CPU reference, culled patches must have no pixel in the visibility oracle
(item buffer of the unculled draw), and optionally no visible sample on a dense sampling of
the patch and no pixel lost in the image drawn from the survivors. Prints a table (progress
on stderr) and optionally writes JSON.

Views (both keep the whole bounding sphere, centre of the bounding box and radius half its
diagonal, inside the view, with a random roll):
  sphere        eye uniformly distributed on the sphere of radius r / sin(fov/2) around the
                centre (2.92 r for 40 degrees), looking at the centre (back-patch paper)
  whole-object  random direction, distance in [1, 2] times that radius, view direction
                turned off-centre as far as the object stays in view (occlusion paper)

Options:
  --views N             number of views (default 100)
  --seed S              random seed of the views (default 1)
  --view-set SET        sphere or whole-object (default sphere)
  --methods A,B,...     methods to run (default: every registered method: frustum,
                        back-patch and occlusion (hiz); back-patch methods are skipped with the
                        reason when the mesh is not a closed, outward-oriented solid, hiz
                        without the oracle)
  --hiz-full            Hi-Z top level at full resolution (default: half, as the paper)
  --hiz-tight           Hi-Z lookup one level finer where 2x2 texels still cover the box
  --tess N              uniform tessellation level of the oracle draws (default 4)
  --level L             adaptive isolation level of the patches (default 2)
  --width W --height H  image size (default 256 x 256)
  --fov DEG             vertical field of view (default 40)
  --reference-every K   compare with the CPU reference on every K-th view (default 1;
                        0: never)
  --no-oracle           skip the oracle (no false-cull or oracle-rate figures)
  --sample N            check culled patches on an (N+1) x (N+1) sampling grid (default 0: off)
  --image-check         draw the survivors of each method and compare with the full draw
  --surface-exact       back-patch tests exact for the surface only, as the papers measure
                        them (default: also conservative for the drawn chord triangles,
                        docs/algorithms/drawn-triangles.md); such culls can take single
                        silhouette pixels, which are then reported but do not fail the run
  --json FILE           write the results as JSON
  --displacement ...    see below; with --displaced-bound all (and --displaced-box all, the
                        default then) the six kernels full-oobb ... con-caf run as methods
  --scheme S            override the subdivision scheme
  --device X            Vulkan device: index or name substring
  --validate            enable the Vulkan validation layers
)";

int run(Args& args) {
  if (!args.positional().empty() && isSceneArgument(args.positional().front()))
    return verifyScene(args);
  const uint32_t views = static_cast<uint32_t>(args.integer("views", 1, 10'000'000).value_or(100));
  const uint64_t seed = static_cast<uint64_t>(args.integer("seed", 0, 1L << 62).value_or(1));
  const frame::ViewSet viewSet = frame::parseViewSet(args.value("view-set").value_or("sphere"));
  const auto methodsText = args.value("methods");
  const uint32_t tess = static_cast<uint32_t>(args.integer("tess", 1, 64).value_or(4));
  PatchOptions patchOptions;
  patchOptions.isolationLevel = static_cast<int>(args.integer("level", 0, 10).value_or(2));
  const uint32_t width = static_cast<uint32_t>(args.integer("width", 1, 16384).value_or(256));
  const uint32_t height = static_cast<uint32_t>(args.integer("height", 1, 16384).value_or(256));
  const double fov = args.number("fov", 1.0, 170.0).value_or(40.0);
  const uint32_t referenceEvery =
      static_cast<uint32_t>(args.integer("reference-every", 0, 1'000'000).value_or(1));
  const bool noOracle = args.flag("no-oracle");
  const int sample = static_cast<int>(args.integer("sample", 0, 256).value_or(0));
  const bool imageCheck = args.flag("image-check");
  const bool hizFull = args.flag("hiz-full");
  const bool hizTight = args.flag("hiz-tight");
  const auto jsonPath = args.value("json");
  const auto device = args.value("device");
  const bool validate = args.flag("validate");
  const bool surfaceExact = args.flag("surface-exact");
  const MeshSource source = meshSourceFromArgs(args);
  const DisplacementChoice displacementChoice = displacementFromArgs(args, true);
  args.finish();
  if (imageCheck && noOracle)
    throw Error("--image-check compares with the oracle's draw; drop --no-oracle");

  std::vector<std::string> methods;
  if (methodsText) {
    methods = splitList(*methodsText);
    for (const auto& m : methods) frame::cullMethod(m);  // reject unknown names early
  } else {
    // Every method but the displaced kernels, which run with --displacement (the ones
    // --displaced-bound and --displaced-box choose).
    for (auto stage :
         {frame::CullStage::Frustum, frame::CullStage::BackPatch, frame::CullStage::Occlusion})
      for (const auto& m : frame::cullMethodNames(stage))
        if (!frame::cullMethod(m).displaced) methods.push_back(m);
    for (const std::string& k : kernelNames(displacementChoice)) methods.push_back(k);
  }

  MeshPatches mesh = meshPatches(loadMeshSource(source), patchOptions);
  // Displaced: no back-patch culling, and the oracle draws back faces too (the displaced
  // surface may fold; its holes at UV seams show the inside).
  if (displacementChoice.map) mesh.backPatch = {false, frame::kDisplacedBackPatchNote};
  const PatchSet& patches = mesh.patches;
  std::optional<bound::DisplacementMap> displacementMap;
  if (displacementChoice.map)
    displacementMap.emplace(adapters::loadDisplacementMap(*displacementChoice.map));
  vulkan::ContextOptions contextOptions;
  contextOptions.device = device.value_or("");
  contextOptions.validation = validate;
  vulkan::Context context(contextOptions);

  frame::VerifyOptions options;
  options.tessellation.uniformLevel = tess;
  options.tessellation.maxLevel = context.info().limits.maxTessellationGenerationLevel;
  options.oracle = !noOracle;
  options.referenceStride = referenceEvery;
  options.samplingGrid = sample;
  options.imageCheck = imageCheck;
  options.drawnTriangles = !surfaceExact;
  options.hiz.fullResolution = hizFull;
  options.hiz.lookup = hizTight ? bound::HiZLookup::Tight : bound::HiZLookup::Paper;
  if (displacementMap) {
    options.displacementMap = &*displacementMap;
    options.uvCorners = mesh.uvCorners;
  }
  frame::CullVerifier verifier(context, patches, methods, mesh.backPatch, options);

  frame::ViewSetOptions viewOptions;
  viewOptions.set = viewSet;
  viewOptions.count = views;
  viewOptions.seed = seed;
  viewOptions.width = width;
  viewOptions.height = height;
  viewOptions.fovyDegrees = fov;
  const auto cameras = frame::randomViews(frame::boundsOf(patches.points), viewOptions);

  std::printf("mesh: %s, %u patches (%u Bezier + %u Gregory), level %d\n", mesh.name.c_str(),
              patches.patchCount(), patches.bezierCount, patches.gregoryCount,
              patchOptions.isolationLevel);
  std::printf("views: %u %s (seed %llu), %ux%u, fov %.1f, tess %u, device %s\n", views,
              frame::toString(viewSet), static_cast<unsigned long long>(seed), width, height, fov,
              tess, context.info().name.c_str());
  if (displacementMap) {
    const bound::DisplacementRange r = displacementMap->displacementRange();
    std::printf(
        "displacement: %s, %ux%u, scale %g, midlevel %g, D in [%g, %g], lod %u; "
        "back-patch culling off (%s)\n",
        displacementMap->name().c_str(), displacementMap->width(), displacementMap->height(),
        displacementMap->scale(), displacementMap->midlevel(), r.dmin, r.dmax,
        displacementMap->maxLod(), frame::kDisplacedBackPatchNote);
  }
  std::printf("back-patch culling: %s (%s)%s\n", mesh.backPatch.enabled ? "on" : "off",
              mesh.backPatch.reason.c_str(),
              surfaceExact ? ", surface-exact" : ", conservative for the drawn triangles");
  std::printf("oracle and image draws: back-facing triangles %s\n",
              verifier.cullBackFaces() ? "culled (closed mesh)" : "drawn");
  for (const auto& [name, why] : verifier.skipped())
    std::printf("skipped %s: %s\n", name.c_str(), why.c_str());
  std::fflush(stdout);

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

  const VerifyVerdict verdict =
      printVerifyTables(verifier.totals(), patches.patchCount(), options.oracle, surfaceExact,
                        sample > 0 || imageCheck);
  const bool ok = verdict.ok, okButSilhouettes = verdict.okButSilhouettes;

  if (jsonPath) {
    nlohmann::ordered_json out;
    out["mesh"] = mesh.name;
    out["patches"] = patches.patchCount();
    out["bezier_patches"] = patches.bezierCount;
    out["gregory_patches"] = patches.gregoryCount;
    out["level"] = patchOptions.isolationLevel;
    out["views"] = views;
    out["view_set"] = frame::toString(viewSet);
    out["seed"] = seed;
    out["width"] = width;
    out["height"] = height;
    out["fov"] = fov;
    out["tess"] = tess;
    out["device"] = context.info().name;
    out["back_patch"] = {{"enabled", mesh.backPatch.enabled},
                         {"reason", mesh.backPatch.reason},
                         {"drawn_triangles", !surfaceExact},
                         {"oracle_culls_back_faces", verifier.cullBackFaces()}};
    out["methods"] = nlohmann::ordered_json::array();
    for (const auto& t : verifier.totals())
      out["methods"].push_back(methodJson(t, patches.patchCount(), options.oracle));
    out["skipped"] = nlohmann::ordered_json::array();
    for (const auto& [name, why] : verifier.skipped())
      out["skipped"].push_back({{"name", name}, {"reason", why}});
    out["ok"] = ok;
    out["ok_except_silhouette_chords"] = okButSilhouettes;
    std::ofstream file(*jsonPath);
    if (!file) throw Error("cannot write " + *jsonPath);
    file << out.dump(2) << "\n";
    std::printf("\nwrote %s\n", jsonPath->c_str());
  }
  if (const vulkan::ValidationLog* log = context.validationLog(); log && log->count() > 0) {
    std::cerr << "validation reported " << log->count() << " messages\n";
    return 1;
  }
  if (!okButSilhouettes)
    std::cerr << "verify: FAILED (a GPU cull outside the reference, a false cull, a visible "
                 "sample or a lost pixel; see the tables)\n";
  return okButSilhouettes ? 0 : 1;
}

const Registration kRegistration(
    {"verify",
     "check every cull method against the CPU reference and the oracle on random views",
     std::string(kUsage) + kSceneVerifyUsage + kDisplacementUsage,
     {"no-oracle", "image-check", "validate", "hiz-full", "hiz-tight", "surface-exact"},
     run});

}  // namespace
}  // namespace osd_cull::cli
