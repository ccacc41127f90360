// osd-cull render: draws a mesh (or the built-in scene) with the tessellation pipeline,
// writes PNG images and prints per-frame statistics.
#include "command.h"
#include "cull_options.h"
#include "cull_report.h"
#include "displacement_args.h"
#include "mesh_patches.h"
#include "mesh_source.h"
#include "scene_render.h"
#include "scene_source.h"

#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/face_varying_uv.h"
#include "osd_cull/scene/default_scene.h"

#include "adapters/load_occluder.h"
#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/cull/cull_pass_displaced.h"
#include "osd_cull/frame/demo_shapes.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/draw/png_io.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/vk/context.h"

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

const char* kUsageHead = R"(Usage: osd-cull render [MESH] --out FILE.png [options]

Draws MESH (or, without MESH, a built-in scene of subdivision tori, a patch sphere and
triangle walls) with the Vulkan tessellation pipeline and writes the image as PNG.
MESH: OBJ (with OpenSubdiv tags), OFF, PLY, STL (Catmull-Clark cages, refined adaptively
into Bézier and Gregory patches) or BPT (Bézier patches, e.g. the Utah teapot).
Prints per frame: wall and GPU time, patches drawn, draw calls, tessellation-evaluation
and fragment-shader invocations (pipeline statistics), and with --cull how many patches
each test culled.

Options:
  --level N              adaptive isolation level, 0..10 (default 2)
  --endcap gregory|bspline  end caps of irregular patches (default gregory)
  --scheme catmark|loop|bilinear  override the scheme (default: file-name prefix)
  --out FILE.png         image of the last frame (required)
  --occluders F[,F...]   OBJ files drawn as triangle occluders (before the patches)
  --width W --height H   image size (default 640 x 480)
  --tess N               uniform tessellation, N segments per patch edge (default 4)
  --adaptive PIXELS      screen-space adaptive tessellation, PIXELS per segment
  --camera E,T,U,FOVY    eye, target and up vectors and vertical field of view in degrees:
                         ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy (default: frame the whole scene)
  --frames N             draw N frames (default 1)
  --orbit DEG            rotate the camera about the up axis by DEG per frame
  --out-dir DIR          also keep every frame as DIR/frame_NNNN.png
  --ids                  also write the item buffer (patch ID + 1 per pixel, 24-bit RGB)
                         as FILE_ids.png and the depth as FILE_depth.png
  --debug-colors         color each patch by its index
  --device X             Vulkan device: index or name substring (default $OSD_CULL_DEVICE,
                         else lavapipe)
  --validate             enable the Vulkan validation layers
  --level N              adaptive isolation level of MESH, 0..10 (default 2)
  --scheme S             override the subdivision scheme of MESH
  --stats FILE.json      write the per-frame figures as JSON
  --status-view          with occlusion: also write FILE_status.png, patches colored by
                         their status (green visible, yellow newly visible, blue frustum-,
                         purple back-patch-, red occlusion-culled) from the camera, and
                         FILE_status_side.png from 90 degrees around the up axis
  --pyramid-dir DIR      with occlusion: write the Hi-Z levels of the last frame as
                         DIR/hiz_level_NN.png
)";

std::string usage() {
  return std::string(kUsageHead) + kCullOptionsUsage + kSceneRenderUsage + kDisplacementUsage;
}

struct Scene {
  PatchSet patches;
  std::vector<frame::TriangleMesh> occluders;
  glm::dvec3 up{0, 0, 1};
  glm::dvec3 viewDirection{0.55, -1.0, 0.45};
  bound::BackPatchValidity backPatch;
  std::vector<glm::dvec2> uvCorners;  ///< 4 per patch, empty without texture coordinates
};

Scene loadScene(const MeshSource& source, const PatchOptions& options) {
  if (!source.path) {
    scene::Scene demo = scene::defaultScene(options);
    Scene s{std::move(demo.patches), std::move(demo.occluders), demo.up, demo.viewDirection, {}};
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
  scene.uvCorners = std::move(mesh.uvCorners);
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
      throw Error("option --" + option + ": '" + item + "' is not a finite number");
    out.push_back(v);
  }
  if (out.size() != count)
    throw Error("option --" + option + ": expected " + std::to_string(count) +
                " comma-separated numbers, got " + std::to_string(out.size()));
  return out;
}

fs::path sibling(const fs::path& out, const std::string& suffix) {
  return out.parent_path() / (out.stem().string() + suffix + ".png");
}

int run(Args& args) {
  if (!args.positional().empty() && isSceneArgument(args.positional().front()))
    return renderScene(args);
  const auto out = args.value("out");
  const uint32_t width = static_cast<uint32_t>(args.integer("width", 1, 16384).value_or(640));
  const uint32_t height = static_cast<uint32_t>(args.integer("height", 1, 16384).value_or(480));
  const auto tess = args.integer("tess", 1, 64);
  const auto adaptive = args.number("adaptive", 0.01, 1e6);
  const auto cameraText = args.value("camera");
  const uint32_t frames = static_cast<uint32_t>(args.integer("frames", 1, 100000).value_or(1));
  const double orbitDegrees = args.number("orbit", -360.0, 360.0).value_or(0.0);
  const auto outDir = args.value("out-dir");
  const bool ids = args.flag("ids");
  const bool debugColors = args.flag("debug-colors");
  const bool validate = args.flag("validate");
  const auto device = args.value("device");
  const PatchOptions patchOptions = patchOptionsFromArgs(args);
  const CullChoice cull = cullChoiceFromArgs(args);
  const auto statsPath = args.value("stats");
  const auto occluderFiles = args.value("occluders");
  const bool statusView = args.flag("status-view");
  const auto pyramidDir = args.value("pyramid-dir");
  const MeshSource source = meshSourceFromArgs(args);
  const DisplacementChoice displacementChoice = displacementFromArgs(args, false);
  args.finish();
  if (!out) throw Error("--out FILE.png is required");
  if (tess && adaptive) throw Error("--tess and --adaptive exclude each other");
  if ((statusView || pyramidDir) && !cull.occlusion())
    throw Error("--status-view and --pyramid-dir need --cull occlusion or --cull all");

  Scene scene = loadScene(source, patchOptions);
  if (occluderFiles) {
    std::stringstream list(*occluderFiles);
    std::string file;
    while (std::getline(list, file, ','))
      if (!file.empty()) scene.occluders.push_back(adapters::loadTriangleMesh(file));
  }
  // Displacement: the map, and back-patch culling off (kDisplacedBackPatchNote).
  std::optional<bound::DisplacementMap> displacementMap;
  if (displacementChoice.map) {
    displacementMap.emplace(adapters::loadDisplacementMap(*displacementChoice.map));
    scene.backPatch = {false, frame::kDisplacedBackPatchNote};
  }
  vulkan::ContextOptions contextOptions;
  contextOptions.device = device.value_or("");
  contextOptions.validation = validate;
  vulkan::Context context(contextOptions);
  std::cout << "device: " << context.info().name << "\n";
  std::cout << "scene: " << scene.patches.source << ": " << scene.patches.bezierCount
            << " Bezier + " << scene.patches.gregoryCount << " Gregory patches, "
            << scene.occluders.size() << " triangle occluders\n";

  frame::GpuPatchSet gpu(context, scene.patches);
  std::unique_ptr<frame::GpuDisplacement> gpuDisplacement;
  if (displacementMap) {
    gpuDisplacement = std::make_unique<frame::GpuDisplacement>(
        context, *displacementMap, scene.uvCorners, scene.patches.patchCount());
    gpu.setDisplacement(gpuDisplacement.get());
    const bound::DisplacementRange r = displacementMap->displacementRange();
    std::cout << "displacement: " << displacementMap->name() << ", " << displacementMap->width()
              << "x" << displacementMap->height() << ", scale " << displacementMap->scale()
              << ", midlevel " << displacementMap->midlevel() << ", D in [" << r.dmin << ", "
              << r.dmax << "], bound "
              << bound::displacedKernelName(displacementChoice.kernels[0].extension,
                                            displacementChoice.kernels[0].box)
              << "; UV seam edges " << countUVSeamEdges(scene.patches, scene.uvCorners) << "\n";
  }
  std::vector<frame::GpuTriangleMesh> occluderMeshes;
  for (const auto& m : scene.occluders) occluderMeshes.emplace_back(context, m);
  std::vector<const frame::GpuTriangleMesh*> occluders;
  for (const auto& m : occluderMeshes) occluders.push_back(&m);

  frame::Bounds bounds = frame::boundsOf(scene.patches.points);
  for (const auto& m : scene.occluders) {
    const frame::Bounds b = frame::boundsOf(m.positions);
    bounds.lo = glm::min(bounds.lo, b.lo);
    bounds.hi = glm::max(bounds.hi, b.hi);
  }
  frame::Camera camera;
  glm::dvec3 pivot = bounds.center(), up = scene.up;
  if (cameraText) {
    const auto v = parseNumbers(*cameraText, 10, "camera");
    const glm::dvec3 eye(v[0], v[1], v[2]), target(v[3], v[4], v[5]);
    up = glm::dvec3(v[6], v[7], v[8]);
    const double d = glm::distance(eye, bounds.center()), r = bounds.radius();
    camera = frame::Camera::lookAt(eye, target, up, v[9], width, height,
                                   std::max(d - r, (d + r) * 1e-4), d + r);
    pivot = target;
  } else {
    camera = frame::frameBounds(bounds, scene.viewDirection, scene.up, 40.0, width, height);
  }

  frame::RenderOptions options;
  options.debugColors = debugColors;
  if (adaptive) {
    options.tessellation.mode = frame::TessellationOptions::Mode::Adaptive;
    options.tessellation.pixelsPerSegment = *adaptive;
  } else {
    options.tessellation.uniformLevel = static_cast<uint32_t>(tess.value_or(4));
  }
  options.tessellation.maxLevel = context.info().limits.maxTessellationGenerationLevel;

  frame::RenderTarget target(context, width, height);
  frame::Renderer renderer(context);
  // Without occlusion: one pass, the cull kernel before it. With occlusion: the two-pass
  // frame with temporal visibility (frame::CullFrame), the same kernel in its third step.
  std::unique_ptr<frame::CullPass> pass;
  std::unique_ptr<frame::CullFrame> cullFrame;
  const frame::CullMesh meshes[] = {{&gpu, &scene.patches}};
  // On a closed, oriented mesh the rasterizer culls back faces in every mode, with and
  // without culling, so that frames compare like for like (Niessner & Loop §6: "backface
  // culling is always turned on"); back-patch culling assumes it too: a patch culled with
  // the drawn-triangle bound could not have drawn a pixel (docs/algorithms/drawn-triangles.md).
  const bool backPatchCulling =
      (cull.mode == "backpatch" || cull.mode == "all") && scene.backPatch.enabled;
  options.cullBackFaces = scene.backPatch.enabled;
  std::cout << "back faces: "
            << (scene.backPatch.enabled
                    ? "culled by the rasterizer (closed, oriented mesh), with or without culling"
                    : "drawn (" + scene.backPatch.reason + ")")
            << "\n";
  frame::CullFrameOptions frameOptions = cull.frame;
  frameOptions.render = options;
  frameOptions.cull = cullSettings(cull, scene.backPatch);
  if (displacementMap) {
    frameOptions.cull.displacementMap = &*displacementMap;
    frameOptions.cull.uvCorners = scene.uvCorners;
    frameOptions.cull.displacedKernel = displacementChoice.kernels[0];
  }
  const std::vector<const frame::CullMethod*>* stages = nullptr;
  if (cull.occlusion()) {
    cullFrame = std::make_unique<frame::CullFrame>(context, renderer, target, meshes, frameOptions);
    stages = &cullFrame->cullPass(0)->stages();
  } else if (cull.enabled()) {
    pass = std::make_unique<frame::CullPass>(context, gpu, scene.patches, frameOptions.cull);
    stages = &pass->stages();
  }
  if (stages) {
    std::cout << "cull: " << cull.mode;
    for (const frame::CullMethod* m : *stages)
      std::cout << (m == stages->front() ? " (" : ", ") << m->name;
    std::cout << (stages->empty() ? "" : ")") << "\n";
    const frame::CullPass& p = pass ? *pass : *cullFrame->cullPass(0);
    if (!p.backPatchNote().empty()) std::cout << "note: " << p.backPatchNote() << "\n";
    if (backPatchCulling)
      std::cout << "back-patch culls: "
                << (cull.surfaceExact ? "surface-exact" : "conservative for the drawn triangles")
                << "; back-facing triangles culled in the draws\n";
  }
  if (cullFrame) {
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
  if (outDir) fs::create_directories(*outDir);
  const frame::PatchDraw draw{&gpu, &scene.patches, 0};
  nlohmann::json jsonFrames = nlohmann::json::array();
  frame::Camera view = camera;
  for (uint32_t f = 0; f < frames; ++f) {
    view = frame::orbit(camera, pivot, up, orbitDegrees * f);
    if (cullFrame) {
      const frame::CullFrameStats stats = cullFrame->render(view, occluders);
      std::printf("%s\n", cullFrameLine(f, stats).c_str());
      jsonFrames.push_back(cullFrameJson(f, stats));
    } else {
      const frame::FrameStats stats =
          pass ? frame::renderCulled(renderer, target, view, *pass, occluders, options)
               : renderer.render(target, view, {&draw, 1}, occluders, options);
      std::printf(
          "frame %u: %.2f ms (gpu %.2f ms), %u patches, %u draws, TES invocations %llu, "
          "fragment invocations %llu\n",
          f, stats.wallMs, stats.gpuMs, stats.patchesDrawn, stats.drawCalls,
          static_cast<unsigned long long>(stats.statistics.tessEvaluationInvocations),
          static_cast<unsigned long long>(stats.statistics.fragmentShaderInvocations));
      nlohmann::json j = plainFrameJson(f, stats);
      if (pass) {
        uint32_t byStage[4] = {0, 0, 0, 0};
        for (uint32_t code : pass->results()) ++byStage[bound::CullCode{code}.stage() & 3u];
        std::printf("  culled %u of %u: frustum %u, back-patch %u\n",
                    scene.patches.patchCount() - stats.patchesDrawn, scene.patches.patchCount(),
                    byStage[1], byStage[2]);
        j["patches"] = scene.patches.patchCount();
        j["drawn"] = stats.patchesDrawn;
        j["culled"] = {{"frustum", byStage[1]}, {"backPatch", byStage[2]}, {"occlusion", 0}};
      }
      jsonFrames.push_back(std::move(j));
    }
    const bool last = f + 1 == frames;
    if (!outDir && !last) continue;
    const auto color = frame::colorImage(width, height, target.readColor(context));
    if (outDir) {
      char name[32];
      std::snprintf(name, sizeof(name), "frame_%04u.png", f);
      frame::writePng(fs::path(*outDir) / name, color);
    }
    if (last) {
      frame::writePng(*out, color);
      std::cout << "wrote " << *out << "\n";
      if (ids) {
        frame::writePng(sibling(*out, "_ids"),
                        frame::itemImage(width, height, target.readItems(context)));
        frame::writePng(sibling(*out, "_depth"),
                        frame::depthImage(width, height, target.readDepth(context)));
        std::cout << "wrote " << sibling(*out, "_ids").string() << " and "
                  << sibling(*out, "_depth").string() << "\n";
      }
    }
  }
  if (statsPath) {
    nlohmann::json doc{{"device", context.info().name},
                       {"scene", scene.patches.source},
                       {"width", width},
                       {"height", height},
                       {"cull", cull.mode},
                       {"frames", jsonFrames}};
    if (cullFrame)
      doc["options"] = {
          {"aggressive", frameOptions.aggressive},
          {"drawMode", toString(frameOptions.drawMode)},
          {"firstFrame", toString(frameOptions.firstFrame)},
          {"hizFullResolution", frameOptions.hiz.fullResolution},
          {"hizLookup", frameOptions.hiz.lookup == bound::HiZLookup::Tight ? "tight" : "paper"},
          {"hizSampler", cullFrame->pyramid().usesSampler()},
          {"hizSinglePass", cullFrame->pyramid().singlePass()}};
    std::ofstream file(*statsPath);
    if (!(file << doc.dump(2) << "\n")) throw Error(*statsPath + ": cannot write");
    std::cout << "wrote " << *statsPath << "\n";
  }
  if (cullFrame && statusView) {
    frame::RenderTarget viewTarget(context, width, height);
    const frame::Camera side = frame::orbit(view, pivot, up, 90.0);
    for (const auto& [statusCamera, suffix] :
         {std::pair{view, "_status"}, std::pair{side, "_status_side"}}) {
      cullFrame->renderStatusView(viewTarget, statusCamera, occluders);
      frame::writePng(sibling(*out, suffix),
                      frame::colorImage(width, height, viewTarget.readColor(context)));
      std::cout << "wrote " << sibling(*out, suffix).string() << "\n";
    }
  }
  if (cullFrame && pyramidDir) {
    const uint32_t n = writePyramidLevels(*pyramidDir, cullFrame->pyramid(), context);
    std::cout << "wrote " << n << " pyramid levels to " << *pyramidDir << "\n";
  }
  if (const vulkan::ValidationLog* log = context.validationLog(); log && log->count() > 0) {
    std::cerr << "validation reported " << log->count() << " messages\n";
    return 1;
  }
  return 0;
}

const Registration kRegistration(
    {"render",
     "draw a mesh or the built-in scene to PNG (optionally culled), print frame statistics",
     usage(),
     {"ids", "debug-colors", "validate", "status-view", "aggressive", "hiz-full", "hiz-tight",
      "surface-exact", "compare"},
     run});

}  // namespace
}  // namespace osd_cull::cli
