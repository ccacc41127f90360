// osd-cull render: draws a mesh (or the built-in scene) with the tessellation pipeline,
// writes PNG images and prints per-frame statistics.
#include "command.h"
#include "cull_options.h"
#include "cull_report.h"
#include "device_options.h"
#include "displacement_args.h"
#include "mesh_patches.h"
#include "mesh_source.h"
#include "option_checks.h"
#include "plan_options.h"
#include "render_args.h"
#include "scene_render.h"
#include "scene_source.h"

#include "osd_cull/frame/verify/crack_count.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/face_varying_uv.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/session/mesh_session.h"

#include "adapters/image_legend.h"
#include "adapters/image_png.h"
#include "adapters/load_occluder.h"
#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/cull/cull_pass_displaced.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/shader_compiler.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

namespace osd_cull::cli {
namespace {

namespace fs = std::filesystem;

const char* kDescription =
    R"(Draws MESH (or, without MESH, a built-in scene of subdivision tori, a patch sphere and
triangle walls) with the Vulkan tessellation pipeline and writes the image as PNG.
Prints per frame: wall and GPU time, patches drawn, draw calls, tessellation-evaluation
and fragment-shader invocations (pipeline statistics), and with --cull how many patches
each test culled.)";

struct Scene {
  PatchSet patches;
  std::vector<frame::TriangleMesh> occluders;
  glm::dvec3 up{0, 0, 1};
  glm::dvec3 viewDirection{0.55, -1.0, 0.45};
  bound::BackPatchValidity backPatch;
  std::vector<std::string> notes;     ///< the loader's notes on the mesh
  std::vector<glm::dvec2> uvCorners;  ///< 4 per patch, empty without texture coordinates
  /// Subtracted from the file's coordinates (a far mesh recentred at load): --camera and
  /// --occluders, given in the file's coordinates, move by it too.
  glm::dvec3 offset{0.0};
};

Scene loadScene(const MeshSource& source, const PatchOptions& options) {
  if (!source.path) {
    scene::Scene demo = scene::defaultScene(options);
    Scene s{
        std::move(demo.patches), std::move(demo.occluders), demo.up, demo.viewDirection, {}, {}};
    // Every object is a closed manifold cage with outward normals (scene/procedural.h
    // tests this), and the walls are occluders, not patches.
    s.backPatch = {true, "built-in scene: closed cages, normals outward by construction"};
    return s;
  }
  if (!fs::exists(*source.path)) throw Error(*source.path + ": no such file");
  const LoadedMesh loaded = loadMeshSource(source);
  MeshPatches mesh = meshPatches(loaded, options);
  Scene scene;
  scene.patches = std::move(mesh.patches);
  scene.backPatch = mesh.backPatch;
  scene.notes = std::move(mesh.notes);
  scene.uvCorners = std::move(mesh.uvCorners);
  scene.offset = mesh.recentreOffset;
  if (loaded.bezier) {  // BPT files (the teapot) are z up
    scene.up = {0, 0, 1};
    scene.viewDirection = {0.6, -1.0, 0.5};
  } else {  // OBJ and the other cage formats are mostly y up
    scene.up = {0, 1, 0};
    scene.viewDirection = {0.45, 0.35, 1.0};
  }
  return scene;
}

std::vector<double> parseNumbers(const std::string& text, size_t count, const std::string& option) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(v))
      throw UsageError("option --" + option + ": '" + item + "' is not a finite number");
    out.push_back(v);
  }
  if (out.size() != count)
    throw UsageError("option --" + option + ": expected " + std::to_string(count) +
                     " comma-separated numbers, got " + std::to_string(out.size()));
  return out;
}

fs::path sibling(const fs::path& out, const std::string& suffix) {
  return out.parent_path() / (out.stem().string() + suffix + ".png");
}

struct StartView {
  frame::Camera camera;
  glm::dvec3 pivot, up;
};

// The first frame's camera: --camera's numbers, else the whole scene framed (occluders
// included) from the format's view direction; the orbit turns about `pivot` and `up`.
StartView startView(const Scene& scene, const std::vector<double>& cameraNumbers, uint32_t width,
                    uint32_t height) {
  frame::Bounds bounds = frame::boundsOf(scene.patches.points);
  for (const auto& m : scene.occluders) bounds = frame::unite(bounds, frame::boundsOf(m.positions));
  StartView s{{}, bounds.center(), scene.up};
  if (cameraNumbers.empty()) {
    s.camera = frame::frameBounds(bounds, scene.viewDirection, scene.up, 40.0, width, height);
    return s;
  }
  const auto& v = cameraNumbers;
  const glm::dvec3 eye = glm::dvec3(v[0], v[1], v[2]) - scene.offset,
                   target = glm::dvec3(v[3], v[4], v[5]) - scene.offset;
  s.up = glm::dvec3(v[6], v[7], v[8]);
  const double d = glm::distance(eye, bounds.center()), r = bounds.radius();
  s.camera = frame::Camera::lookAt(eye, target, s.up, v[9], width, height,
                                   std::max(d - r, (d + r) * 1e-4), d + r);
  s.pivot = target;
  return s;
}

frame::RenderOptions renderOptions(const RenderArgs& args, vulkan::Context& context,
                                   const DisplacementChoice& displacement) {
  frame::RenderOptions options;
  options.debugColors = args.debugColors;
  if (args.adaptive > 0.0) {
    options.tessellation.mode = frame::TessellationOptions::Mode::Adaptive;
    options.tessellation.pixelsPerSegment = args.adaptive;
  } else {
    options.tessellation.uniformLevel = args.tess;
  }
  options.tessellation.maxLevel = context.info().limits.maxTessellationGenerationLevel;
  options.tessellation.displaced = displacement.tessellation;
  return options;
}

void printDisplacement(const bound::DisplacementMap& map, const DisplacementChoice& displacement,
                       const Scene& scene) {
  const bound::DisplacementRange r = map.displacementRange();
  std::cout << "displacement: " << map.name() << ", " << map.width() << "x" << map.height()
            << ", scale " << map.scale() << ", midlevel " << map.midlevel() << ", D in [" << r.dmin
            << ", " << r.dmax << "], bound "
            << bound::displacedKernelName(displacement.kernels[0].extension,
                                          displacement.kernels[0].box)
            << "; UV seam edges " << countUVSeamEdges(scene.patches, scene.uvCorners) << "\n";
}

// The fixed stages (a plan says its own): the kernel's stages, notes, the two-pass options.
void printCullSetup(session::MeshSession& meshSession, const CullChoice& cull,
                    const frame::CullFrameOptions& frameOptions, bool backPatchCulling) {
  if (const frame::CullPass* p = meshSession.cullPass()) {
    const std::vector<const frame::CullMethod*>& stages = p->stages();
    std::cout << "cull: " << cull.mode;
    for (const frame::CullMethod* m : stages)
      std::cout << (m == stages.front() ? " (" : ", ") << m->name;
    std::cout << (stages.empty() ? "" : ")") << "\n";
    if (!p->backPatchNote().empty()) std::cout << "note: " << p->backPatchNote() << "\n";
    if (backPatchCulling)
      std::cout << "back-patch culls: "
                << (cull.surfaceExact ? "surface-exact" : "conservative for the drawn triangles")
                << "; back-facing triangles culled in the draws\n";
  }
  if (const frame::CullFrame* cullFrame = meshSession.cullFrame()) {
    const auto& layout = cullFrame->pyramid().layout();
    std::cout << "occlusion: " << (frameOptions.aggressive ? "aggressive" : "two passes")
              << ", draw mode " << toString(frameOptions.drawMode) << ", first frame "
              << toString(frameOptions.firstFrame) << "; Hi-Z " << layout.levelCount
              << " levels from " << layout.levelWidth(0) << "x" << layout.levelHeight(0) << ", "
              << (cullFrame->pyramid().singlePass()
                      ? "single-pass"
                      : (cullFrame->pyramid().usesSampler() ? "min/max sampler" : "4-tap"))
              << " build, "
              << (frameOptions.hiz.lookup == bound::HiZLookup::Tight ? "tight" : "paper")
              << " lookup\n";
  }
}

// One frame's line on stdout and its JSON object (one layout per kind of frame): a
// one-pass culled frame appends what it culled (and its cluster tests) to the same line.
nlohmann::json printFrame(uint32_t f, const session::SessionFrame& frame) {
  if (frame.kind == session::FrameKind::TwoPass) {
    std::printf("%s\n", cullFrameLine(f, frame.stats).c_str());
    return cullFrameJson(f, frame.stats);
  }
  const frame::FrameStats& stats = frame.onePass;
  std::printf(
      "frame %u: %.2f ms (gpu %.2f ms), %u patches, %u draws, TES invocations %llu, "
      "fragment invocations %llu",
      f, stats.wallMs, stats.gpuMs, stats.patchesDrawn, stats.drawCalls,
      static_cast<unsigned long long>(stats.statistics.tessEvaluationInvocations),
      static_cast<unsigned long long>(stats.statistics.fragmentShaderInvocations));
  nlohmann::json j = plainFrameJson(f, stats);
  if (frame.kind == session::FrameKind::OnePass) {
    const frame::CullFrameStats& c = frame.stats;
    std::printf("; culled %u of %u: frustum %u, back-patch %u", c.patchesTotal - c.survivors,
                c.patchesTotal, c.culledFrustum, c.culledBackPatch);
    j["patches"] = c.patchesTotal;
    j["drawn"] = c.survivors;
    j["ms"]["cull"] = nullptr;  // not apart: pass1 spans the dispatch and the draws
    j["culled"] = {
        {"frustum", c.culledFrustum}, {"backPatch", c.culledBackPatch}, {"occlusion", 0}};
    if (c.clusters.clusters > 0) {  // --clusters
      const frame::ClusterCounts& k = c.clusters;
      std::printf("; clusters %u: culled %u, accepted %u, undecided %u, per-patch invocations %u",
                  k.clusters, k.culled, k.accepted, k.undecided, k.perPatchInvocations);
      j["clusters"] = {{"tests", k.clusters},
                       {"culled", k.culled},
                       {"accepted", k.accepted},
                       {"undecided", k.undecided},
                       {"perPatchInvocations", k.perPatchInvocations}};
    }
  }
  std::printf("\n");
  return j;
}

// The frame's image into --out-dir, and the last one into --out (with --ids its item and
// depth images).
void writeFrameImages(const RenderArgs& args, vulkan::Context& context,
                      const frame::RenderTarget& target, uint32_t f, bool last) {
  if (args.outDir.empty() && !last) return;
  const uint32_t width = target.width(), height = target.height();
  // --debug-colors: the strip shows the colours of the first patches' indices.
  const adapters::PngImage plain = adapters::colorImage(width, height, target.readColor(context));
  const auto color =
      args.debugColors ? adapters::withLegend(plain, adapters::patchIndexLegend()) : plain;
  if (!args.outDir.empty()) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%04u.png", f);
    adapters::writePng(fs::path(args.outDir) / name, color);
  }
  if (!last) return;
  const fs::path out = args.out;
  adapters::writePng(out, color);
  std::cout << "wrote " << out << "\n";
  if (!args.ids) return;
  adapters::writePng(sibling(out, "_ids"),
                     adapters::itemImage(width, height, target.readItems(context)));
  adapters::writePng(sibling(out, "_depth"),
                     adapters::depthImage(width, height, target.readDepth(context)));
  std::cout << "wrote " << sibling(out, "_ids").string() << " and "
            << sibling(out, "_depth").string() << "\n";
}

// --status-view and --pyramid-dir of the last two-pass frame.
void writeStatusAndPyramid(const RenderArgs& args, vulkan::Context& context,
                           frame::CullFrame& cullFrame,
                           std::span<const frame::GpuTriangleMesh* const> occluders,
                           const frame::Camera& view, const glm::dvec3& pivot, const glm::dvec3& up,
                           std::span<const glm::dvec3> points) {
  const fs::path out = args.out;
  if (args.statusView) {
    const uint32_t width = view.width, height = view.height;
    frame::RenderTarget viewTarget(context, width, height);
    // Without --camera both views frame the patches' control points tightly from their
    // directions (the frame's camera fits the bounding sphere: a flat mesh got a third).
    const frame::Camera side = frame::orbit(view, pivot, up, 90.0);
    const auto framed = [&](const frame::Camera& c) {
      return args.camera.empty() ? frame::frameTightly(c, points) : c;
    };
    for (const auto& [statusCamera, suffix] :
         {std::pair{framed(view), "_status"}, std::pair{framed(side), "_status_side"}}) {
      cullFrame.renderStatusView(viewTarget, statusCamera, occluders);
      adapters::writePng(
          sibling(out, suffix),
          adapters::withLegend(adapters::colorImage(width, height, viewTarget.readColor(context)),
                               adapters::statusLegend()));
      std::cout << "wrote " << sibling(out, suffix).string() << "\n";
    }
  }
  if (!args.pyramidDir.empty()) {
    const uint32_t n = writePyramidLevels(args.pyramidDir, cullFrame.pyramid(), context);
    std::cout << "wrote " << n << " pyramid levels to " << args.pyramidDir << "\n";
  }
}

// The mesh form's options checked, and every output, before the (possibly long) run; the
// numbers of --camera.
std::vector<double> checkMeshForm(const RenderArgs& args, const CullChoice& cull) {
  if (args.compare) throw UsageError("--compare applies to the scene form (render SCENE)");
  if (args.out.empty()) throw UsageError("--out FILE.png is required");
  if ((args.statusView || !args.pyramidDir.empty()) && !cull.occlusion())
    throw UsageError("--status-view and --pyramid-dir need --cull occlusion or --cull all");
  std::vector<double> cameraNumbers;
  if (!args.camera.empty()) cameraNumbers = parseNumbers(args.camera, 10, "camera");
  checkOutputFile(args.out, "--out", {".png"});
  if (!args.stats.empty()) checkOutputFile(args.stats, "--stats", {".json"});
  if (!args.outDir.empty()) prepareOutputDirectory(args.outDir, "--out-dir");
  if (!args.pyramidDir.empty()) prepareOutputDirectory(args.pyramidDir, "--pyramid-dir");
  return cameraNumbers;
}

// The two-pass frame's options, as --stats records them.
nlohmann::json twoPassOptionsJson(const frame::CullFrameOptions& o, const frame::CullFrame& f) {
  return {{"aggressive", o.aggressive},
          {"drawMode", toString(o.drawMode)},
          {"firstFrame", toString(o.firstFrame)},
          {"hizFullResolution", o.hiz.fullResolution},
          {"hizLookup", o.hiz.lookup == bound::HiZLookup::Tight ? "tight" : "paper"},
          {"hizSampler", f.pyramid().usesSampler()},
          {"hizSinglePass", f.pyramid().singlePass()}};
}

void writeJson(const std::string& path, const nlohmann::json& doc) {
  std::ofstream file(path);
  if (!(file << doc.dump(2) << "\n")) throw Error(path + ": cannot write");
  std::cout << "wrote " << path << "\n";
}

/// \brief Adds the --occluders OBJ files to the scene, moved by its recentring offset (they
/// are given in the file's coordinates).
void addOccluders(Scene& scene, const std::string& files) {
  for (const std::string& file : splitList(files))
    if (!file.empty()) {
      scene.occluders.push_back(adapters::loadTriangleMesh(file));
      for (glm::dvec3& p : scene.occluders.back().positions) p -= scene.offset;
    }
}

/// \brief The displacement map --displacement names, loaded, if any; with one, back-patch
/// culling is off for the scene (kDisplacedBackPatchNote).
std::optional<bound::DisplacementMap> loadDisplacement(const DisplacementChoice& displacement,
                                                       Scene& scene) {
  std::optional<bound::DisplacementMap> map;
  if (displacement.map) {
    map.emplace(adapters::loadDisplacementMap(*displacement.map));
    scene.backPatch = {false, frame::kDisplacedBackPatchNote};
  }
  return map;
}

/// \brief The lines that open the output: the device, the scene's patches and occluders,
/// the loader's notes.
void printSceneHeader(const vulkan::Context& context, const Scene& scene) {
  std::cout << "device: " << context.info().name << "\n";
  std::cout << "scene: " << scene.patches.source << ": " << scene.patches.bezierCount
            << " Bezier + " << scene.patches.gregoryCount << " Gregory patches, "
            << scene.occluders.size() << " triangle occluders\n";
  for (const std::string& note : scene.notes) std::cout << "note: " << note << "\n";
}

/// \brief The scene on the device: its patches (displaced by the map, if any) and its
/// triangle occluders.
struct GpuScene {
  GpuScene(vulkan::Context& context, const Scene& scene, const bound::DisplacementMap* map)
      : patches(context, scene.patches) {
    if (map) {
      displacement = std::make_unique<frame::GpuDisplacement>(context, *map, scene.uvCorners,
                                                              scene.patches.patchCount());
      patches.setDisplacement(displacement.get());
    }
    for (const auto& m : scene.occluders) occluderMeshes.emplace_back(context, m);
    for (const auto& m : occluderMeshes) occluders.push_back(&m);
  }

  frame::GpuPatchSet patches;
  std::unique_ptr<frame::GpuDisplacement> displacement;
  std::vector<frame::GpuTriangleMesh> occluderMeshes;
  std::vector<const frame::GpuTriangleMesh*> occluders;  ///< of occluderMeshes
};

/// \brief The `back faces:` line: whether the rasterizer culls them (on a closed, oriented
/// mesh) or draws them, and why.
void printBackFaces(const bound::BackPatchValidity& backPatch) {
  std::cout << "back faces: "
            << (backPatch.enabled
                    ? "culled by the rasterizer (closed, oriented mesh), with or without culling"
                    : "drawn (" + backPatch.reason + ")")
            << "\n";
}

/// \brief What the session draws: the render options, the cull stages chosen (or the
/// plan's, with a planner) with the scene's back-patch validity, and the displacement map
/// with its kernel.
session::MeshSessionOptions meshSessionOptions(const Scene& scene, const CullChoice& cull,
                                               const frame::RenderOptions& options,
                                               const bound::DisplacementMap* map,
                                               const DisplacementChoice& displacement) {
  session::MeshSessionOptions sessionOptions;
  sessionOptions.name = scene.patches.source;
  sessionOptions.view = "render";
  frame::CullFrameOptions& frameOptions = sessionOptions.frame;
  frameOptions = cull.frame;
  frameOptions.render = options;
  frameOptions.cull = cullSettings(cull, scene.backPatch);
  if (map) {
    frameOptions.cull.displacementMap = map;
    frameOptions.cull.uvCorners = scene.uvCorners;
    frameOptions.cull.displacedKernel = displacement.kernels[0];
  }
  return sessionOptions;
}

/// \brief The frames drawn: their JSON objects (for --stats) and the last frame's camera.
struct RenderedFrames {
  nlohmann::json json = nlohmann::json::array();
  frame::Camera lastView;
};

/// \brief Draws --frames frames, the camera orbiting the start view by --orbit degrees a
/// frame; prints each frame (and each plan change) and writes its images.
RenderedFrames renderFrames(const RenderArgs& args, vulkan::Context& context,
                            session::MeshSession& meshSession, const frame::RenderTarget& target,
                            const StartView& start) {
  const uint32_t frames = args.frames.value_or(1);
  RenderedFrames rendered;
  rendered.lastView = start.camera;
  std::optional<plan::Plan> lastPlan;
  for (uint32_t f = 0; f < frames; ++f) {
    rendered.lastView = frame::orbit(start.camera, start.pivot, start.up, args.orbitDegrees * f);
    const session::SessionFrame frame = meshSession.render(rendered.lastView);
    if (frame.plan && frame.planChanged)
      printPlanChange(lastPlan ? &*lastPlan : nullptr, *frame.plan, std::cout, "", args.verbose);
    if (frame.plan) lastPlan = frame.plan;
    rendered.json.push_back(printFrame(f, frame));
    writeFrameImages(args, context, target, f, f + 1 == frames);
  }
  return rendered;
}

/// \brief Displaced: the pixels where the surface opens in the last view (UV seams; edges
/// elsewhere get equal levels on both sides), drawn unculled with back faces culled and not
/// on a target of the frame's size (the frame's left alone), printed.
uint32_t countLastViewCracks(vulkan::Context& context, frame::Renderer& renderer,
                             const frame::RenderTarget& target, const frame::Camera& view,
                             const frame::PatchDraw& draw, const frame::RenderOptions& options) {
  frame::RenderTarget crackTarget(context, target.width(), target.height());
  const uint32_t crackPixels = frame::countCracks(context, renderer, crackTarget, view, draw,
                                                  options, frame::kSeamCrackWidth);
  std::printf(
      "cracks: %u pixels in the last view (displaced surface open at UV seams, back "
      "faces culled; --displaced-tess %s)\n",
      crackPixels, frame::toString(options.tessellation.displaced));
  return crackPixels;
}

/// \brief --stats: the run's frames, summary, crack pixels and two-pass options as JSON.
void writeStats(const std::string& path, const vulkan::Context& context, const Scene& scene,
                const frame::RenderTarget& target, const std::string& cull,
                const RenderedFrames& rendered, const session::SessionSummary& summary,
                const frame::CullFrame* cullFrame, const frame::CullFrameOptions& frameOptions,
                std::optional<uint32_t> crackPixels) {
  nlohmann::json doc{{"device", context.info().name},
                     {"scene", scene.patches.source},
                     {"width", target.width()},
                     {"height", target.height()},
                     {"cull", cull},
                     {"frames", rendered.json},
                     {"summary", summaryJson(summary)}};
  if (crackPixels) doc["crack_pixels"] = *crackPixels;
  if (cullFrame) doc["options"] = twoPassOptionsJson(frameOptions, *cullFrame);
  writeJson(path, doc);
}

/// \brief The shader cache's line; the exit code: 1 when validation reported messages.
int finishRun(const vulkan::Context& context) {
  const vulkan::ShaderCacheStats shaders = vulkan::shaderCacheStats();
  std::printf("shader variants: %zu from the library's build-time SPIR-V, %.1f ms\n",
              shaders.embedded, shaders.milliseconds);
  if (const vulkan::ValidationLog* log = context.validationLog(); log && log->count() > 0) {
    std::cerr << "validation reported " << log->count() << " messages\n";
    return 1;
  }
  return 0;
}

int run(const RenderArgs& args) {
  if (args.source.path && isSceneArgument(*args.source.path)) return renderScene(args);
  const uint32_t width = args.width.value_or(640), height = args.height.value_or(480);
  const CullChoice cull = cullChoice(args.cull);
  const std::vector<double> cameraNumbers = checkMeshForm(args, cull);

  Scene scene = loadScene(args.source, args.patchOptions);
  addOccluders(scene, args.occluders);
  const DisplacementChoice displacement = displacementChoice(args.displacement, false);
  // Displacement: the map, and back-patch culling off (kDisplacedBackPatchNote).
  const std::optional<bound::DisplacementMap> displacementMap =
      loadDisplacement(displacement, scene);
  const bound::DisplacementMap* map = displacementMap ? &*displacementMap : nullptr;
  vulkan::Context context(args.device);
  printSceneHeader(context, scene);
  GpuScene gpu(context, scene, map);
  if (map) printDisplacement(*map, displacement, scene);

  const StartView start = startView(scene, cameraNumbers, width, height);
  frame::RenderOptions options = renderOptions(args, context, displacement);
  frame::RenderTarget target(context, width, height);
  frame::Renderer renderer(context);
  // On a closed, oriented mesh the rasterizer culls back faces in every mode, with and
  // without culling, so that frames compare like for like (Niessner & Loop §6: "backface
  // culling is always turned on"); back-patch culling assumes it too: a patch culled with
  // the drawn-triangle bound could not have drawn a pixel (docs/algorithms/drawn-triangles.md).
  const bool backPatchCulling =
      (cull.mode == "backpatch" || cull.mode == "all") && scene.backPatch.enabled;
  options.cullBackFaces = scene.backPatch.enabled;
  printBackFaces(scene.backPatch);
  const session::MeshSessionOptions sessionOptions =
      meshSessionOptions(scene, cull, options, map, displacement);
  // The effect plan (docs/algorithms/plan.md): without --cull, each frame's stages are the
  // planner's, drawn by the session (session/mesh_session.h), which keeps every
  // configuration's visibility status across plan changes.
  const std::unique_ptr<plan::Planner> planner =
      makePlanner(args.plan, context, !args.cull.mode.empty(),
                  cull.backPatchMethodGiven ? cull.backPatchMethod : "", std::cout);
  session::MeshSession meshSession(context, renderer, target, gpu.patches, scene.patches,
                                   gpu.occluders, sessionOptions, planner.get());
  printCullSetup(meshSession, cull, sessionOptions.frame, backPatchCulling);
  const RenderedFrames rendered = renderFrames(args, context, meshSession, target, start);
  std::optional<uint32_t> crackPixels;
  if (map)
    crackPixels = countLastViewCracks(context, renderer, target, rendered.lastView,
                                      {&gpu.patches, &scene.patches, 0}, options);
  const session::SessionSummary summary = meshSession.summary();
  std::cout << summary.text() << "\n";
  if (!args.stats.empty())
    writeStats(args.stats, context, scene, target, planner ? std::string("plan") : cull.mode,
               rendered, summary, meshSession.cullFrame(), sessionOptions.frame, crackPixels);
  if (frame::CullFrame* cullFrame = meshSession.cullFrame())
    writeStatusAndPyramid(args, context, *cullFrame, gpu.occluders, rendered.lastView, start.pivot,
                          start.up, scene.patches.points);
  return finishRun(context);
}

Runner setup(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  addMeshOptions(app, args->source);
  addPatchOptions(app, args->patchOptions);
  app.add_option("--out", args->out,
                 "image of the last frame (required; a scene: of its first view)")
      ->type_name("FILE.png");
  app.add_option("--occluders", args->occluders,
                 "OBJ files drawn as triangle occluders (before the patches)")
      ->type_name("F[,F...]");
  addSizeOptions(app, args->width, args->height, 1, "640 x 480; a scene: its own");
  CLI::Option* tess = app.add_option("--tess", args->tess,
                                     "uniform tessellation, N segments per patch edge (default 4)")
                          ->type_name("N")
                          ->check(integerIn(1, 64));
  app.add_option("--adaptive", args->adaptive,
                 "screen-space adaptive tessellation, PIXELS per segment")
      ->type_name("PIXELS")
      ->check(numberIn(0.01, 1e6))
      ->excludes(tess);
  app.add_option("--camera", args->camera,
                 "eye, target and up vectors and vertical field of view in degrees:\n"
                 "ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy (default: frame the whole scene)")
      ->type_name("E,T,U,FOVY");
  addOptional(app, "--frames", args->frames, "draw N frames (default 1; a scene: its frameCount)")
      ->type_name("N")
      ->check(integerIn(1, 1000000));
  app.add_option("--orbit", args->orbitDegrees,
                 "rotate the camera about the up axis by DEG per frame")
      ->type_name("DEG")
      ->check(numberIn(-360.0, 360.0));
  app.add_option("--out-dir", args->outDir,
                 "also keep every frame as DIR/frame_NNNN.png (a scene:\n"
                 "DIR/<view>_NNNN.png)")
      ->type_name("DIR");
  app.add_flag("--compare", args->compare,
               "a scene: also draw every frame without culling (same tessellation,\n"
               "back-face culling, image size) and print what culling saved");
  app.add_flag("--ids", args->ids,
               "also write the item buffer (patch ID + 1 per pixel, 24-bit RGB)\n"
               "as FILE_ids.png and the depth as FILE_depth.png");
  app.add_flag("--debug-colors", args->debugColors, "color each patch by its index");
  app.add_flag("--verbose", args->verbose,
               "print each plan whole: every stage on or off with its reason, and\n"
               "what changed at a plan change (default: the plan's one-line headline)");
  app.add_option("--stats", args->stats, "write the per-frame figures as JSON")
      ->type_name("FILE.json");
  addDeviceOptions(app, args->device);
  addCullOptions(app, args->cull);
  addPlanOptions(app, args->plan);
  app.add_flag("--status-view", args->statusView,
               "with occlusion: also write FILE_status.png, patches colored by\n"
               "their status (green visible, yellow newly visible, blue frustum-,\n"
               "purple back-patch-, red occlusion-culled) from the camera, and\n"
               "FILE_status_side.png from 90 degrees around the up axis; a scene:\n"
               "only DIR/<view>_status_NNNN.png (needs --out-dir), seen from 120\n"
               "degrees around the view's up axis through the scene's centre")
      ->group("Culling");
  app.add_option("--pyramid-dir", args->pyramidDir,
                 "with occlusion: write the Hi-Z levels of the last frame as\n"
                 "DIR/hiz_level_NN.png")
      ->type_name("DIR")
      ->group("Culling");
  addDisplacementOptions(app, args->displacement, false);
  return [args] { return run(*args); };
}

const Registration kRegistration(
    {"render",
     "draw a mesh or the built-in scene to PNG (optionally culled), print frame statistics",
     kDescription, setup, kSceneRenderUsage});

}  // namespace
}  // namespace osd_cull::cli
