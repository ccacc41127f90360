// bench-occlusion: Hi-Z occlusion culling with temporal visibility (Niessner & Loop), the
// figures of docs/results/occlusion.md, each printed as a Markdown table:
//  1. occlusion cull rate over whole-object views (paper §6.2: BigGuy 26.8%, after one more
//     level 42.9%) next to the oracle rate (patches with no pixel), per scene;
//  2. cull rate against rotation speed 0-10 degrees per frame (paper Fig. 9 right);
//  3. frame time and TES invocations with and without culling on the default scene at tess
//     factors 4, 16, 32 (ratios from the same run; the culled frame is one submission) and
//     the cull overhead (pyramid + cull) as a share of the culled frame, from the same
//     frames in the diagnostic mode (one submission per pass);
//  4. a long sequence with fast rotation: pixels that differ from the unculled image;
//  5. the first frame under each first-frame policy (all, half, none visible before).
//
//   bench-occlusion [--width 1024] [--height 768] [--views 1000] [--orbit-degrees 360]
//                   [--sequence 300] [--repeats 3] [--only 12345]
//                   [--scenes default,bigguy0,bigguy1,bigguy2] [--device X] [--csv FILE]
//                   [--draw-back-faces]
//
// --csv FILE writes the rotation sweep (2) as CSV (scripts/plots/occlusion_rotation.py
// draws it). Like for like: wherever a scene is closed and oriented (the back-patch
// validity), the rasterizer culls back faces in the culled and in the unculled draws (the
// paper's setting, Niessner & Loop §6: "backface culling is always turned on"; the oracle
// keeps drawing both sides); --draw-back-faces draws them on both sides instead. Progress
// goes to stderr.
#include "adapters/load_mesh.h"
#include "bench_support.h"
#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/frame/verify/visibility_oracle.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/vk/context.h"

#include <opensubdiv/far/primvarRefiner.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace osd_cull;

struct Options {
  uint32_t width = 1024, height = 768, views = 1000, sequence = 300;
  double orbitDegrees = 360.0;
  uint32_t repeats = 3;
  std::string only = "12345";
  std::string scenes = "default,bigguy0,bigguy1,bigguy2";
  std::string device;
  std::string csv;             ///< rotation sweep as CSV, if set
  bool drawBackFaces = false;  ///< no rasterizer back-face culling, even on closed meshes
};

using osd_cull::bench::progress;

// False after --help.
bool parse(int argc, char** argv, Options& o) {
  return bench::CommandLine("bench-occlusion", "bench_occlusion.cpp")
      .imageAndDevice(o.width, o.height, o.repeats, o.device)
      .number("--views", o.views, 1)
      .real("--orbit-degrees", o.orbitDegrees, 10.0)
      .number("--sequence", o.sequence, 1)
      .text("--only", o.only)
      .text("--scenes", o.scenes)
      .text("--csv", o.csv)
      .flag("--draw-back-faces", o.drawBackFaces)
      .parse(argc, argv);
}

using osd_cull::bench::median;

struct Scene {
  std::string name;
  PatchSet patches;
  std::vector<frame::TriangleMesh> occluders;
  glm::dvec3 up{0, 0, 1};
  glm::dvec3 viewDirection{0.55, -1.0, 0.45};
  bound::BackPatchValidity validity;  ///< whether the back-patch stage may run
};

// A scene on the device: patches, occluders and a renderer.
struct GpuScene {
  const Scene& scene;
  frame::GpuPatchSet gpu;
  std::vector<frame::GpuTriangleMesh> meshes;
  std::vector<const frame::GpuTriangleMesh*> occluders;
  frame::Bounds bounds;
  GpuScene(vulkan::Context& context, const Scene& s)
      : scene(s), gpu(context, s.patches), bounds(frame::boundsOf(s.patches.points)) {
    for (const auto& m : s.occluders) meshes.emplace_back(context, m);
    for (const auto& m : meshes) occluders.push_back(&m);
  }
  frame::CullMesh mesh() { return {&gpu, &scene.patches}; }
};

glm::dvec3 randomDirection(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), a(0.0, 2.0 * std::numbers::pi);
  const double z = u(rng), phi = a(rng), s = std::sqrt(1.0 - z * z);
  return {s * std::cos(phi), s * std::sin(phi), z};
}

// Up vector not parallel to the view direction.
glm::dvec3 upFor(const glm::dvec3& direction, const glm::dvec3& up) {
  return std::abs(glm::dot(glm::normalize(direction), up)) > 0.95 ? glm::dvec3(1, 0, 0) : up;
}

// The frame's default stages (frustum and Hi-Z occlusion) or, with `all`, frustum,
// tangent-plane back-patch (where valid) and Hi-Z occlusion in the same kernel. Back faces
// are culled by the rasterizer where the scene allows it; the unculled frames of the
// benchmark draw with the same RenderOptions.
frame::CullFrameOptions cullOptions(const Options& options, const Scene& scene, uint32_t tess,
                                    bool all = false) {
  frame::CullFrameOptions o;
  o.render.tessellation.uniformLevel = tess;
  o.render.cullBackFaces = scene.validity.enabled && !options.drawBackFaces;
  if (all) o.cull = {true, "tangent-plane", "hiz", scene.validity};
  return o;
}

// 1. Occlusion and oracle rates over random whole-object views. With every patch visible
// before the frame, the first pass draws them all, so the pyramid holds the complete depth:
// the rate a static camera settles at.
void cullRates(vulkan::Context& context, const Scene& scene, const Options& o) {
  GpuScene g(context, scene);
  frame::RenderTarget target(context, o.width, o.height), oracleTarget(context, o.width, o.height);
  frame::Renderer renderer(context);
  frame::VisibilityOracle oracle(context);
  const frame::CullMesh meshes[] = {g.mesh()};
  frame::CullFrame cull(context, renderer, target, meshes, cullOptions(o, scene, 4));
  frame::CullFrameOptions tightOptions = cullOptions(o, scene, 4);
  tightOptions.hiz.lookup = bound::HiZLookup::Tight;
  frame::CullFrame tight(context, renderer, target, meshes, tightOptions);
  frame::CullFrame all(context, renderer, target, meshes, cullOptions(o, scene, 4, true));
  std::mt19937_64 rng(2012);
  uint64_t culled = 0, culledTight = 0, culledAll = 0, invisible = 0, total = 0;
  for (uint32_t v = 0; v < o.views; ++v) {
    if (v % 100 == 0) progress("1. " + scene.name + ": view " + std::to_string(v));
    const glm::dvec3 dir = randomDirection(rng);
    const frame::Camera cam =
        frame::frameBounds(g.bounds, dir, upFor(dir, scene.up), 40.0, o.width, o.height);
    cull.reset(frame::FirstFrame::AllVisible);
    const auto s = cull.render(cam, g.occluders);
    tight.reset(frame::FirstFrame::AllVisible);
    culledTight += tight.render(cam, g.occluders).culledOcclusion;
    all.reset(frame::FirstFrame::AllVisible);
    culledAll += all.render(cam, g.occluders).culled();
    const auto counts = oracle.query(renderer, oracleTarget, cam, g.gpu, &scene.patches,
                                     g.occluders, cull.options().render.tessellation);
    culled += s.culledOcclusion;
    invisible += s.patchesTotal - counts.visiblePatchCount();
    total += s.patchesTotal;
  }
  std::printf("| %s | %u | %u | %.1f%% | %.1f%% | %.1f%% | %.1f%% |\n", scene.name.c_str(),
              scene.patches.patchCount(), o.views, 100.0 * culled / total,
              100.0 * culledTight / total, 100.0 * culledAll / total, 100.0 * invisible / total);
  std::fflush(stdout);
}

// 2. Cull rate while the camera orbits the object at `speed` degrees per frame, over one
// orbit of `--orbit-degrees` (every speed sees the same views). Frame 0 (everything visible
// before) is left out. Speed 0 is the static camera at the orbit's views every 10 degrees,
// each settled: a first frame with everything visible before it, then the counted frame
// with the same camera. Besides the occlusion cull rate (patches the test culls) it counts
// patches not drawn at all in the frame: culled patches that were visible last frame are
// still drawn in pass 1. `csv`, if open, gets one row per speed.
void rotationRates(vulkan::Context& context, const Scene& scene, const Options& o, FILE* csv) {
  GpuScene g(context, scene);
  frame::RenderTarget target(context, o.width, o.height);
  frame::Renderer renderer(context);
  const frame::CullMesh meshes[] = {g.mesh()};
  frame::CullFrame cull(context, renderer, target, meshes, cullOptions(o, scene, 4));
  const frame::Camera start =
      frame::frameBounds(g.bounds, scene.viewDirection, scene.up, 40.0, o.width, o.height);
  for (double speed = 0.0; speed <= 10.0; speed += 1.0) {
    progress("2. " + scene.name + ": " + std::to_string(int(speed)) + " degrees per frame");
    uint64_t culled = 0, total = 0, pass2 = 0, drawn = 0, frames = 0;
    auto count = [&](const frame::CullFrameStats& s) {
      culled += s.culledOcclusion;
      total += s.patchesTotal;
      pass2 += s.drawnPass2;
      drawn += s.drawnPass1 + s.drawnPass2;
      ++frames;
    };
    if (speed == 0.0) {
      for (double a = 0.0; a < o.orbitDegrees; a += 10.0) {
        const frame::Camera cam = frame::orbit(start, g.bounds.center(), scene.up, a);
        cull.reset(frame::FirstFrame::AllVisible);
        cull.render(cam, g.occluders);
        count(cull.render(cam, g.occluders));
      }
    } else {
      cull.reset(frame::FirstFrame::AllVisible);
      const auto n = static_cast<uint32_t>(std::lround(o.orbitDegrees / speed));
      for (uint32_t f = 0; f <= n; ++f) {
        const auto s =
            cull.render(frame::orbit(start, g.bounds.center(), scene.up, speed * f), g.occluders);
        if (f > 0) count(s);
      }
    }
    const double rate = 100.0 * double(culled) / double(total);
    const double notDrawn = 100.0 * double(total - drawn) / double(total);
    std::printf("| %s | %.0f | %llu | %.1f%% | %.1f%% | %.1f |\n", scene.name.c_str(), speed,
                static_cast<unsigned long long>(frames), rate, notDrawn,
                double(pass2) / double(frames));
    std::fflush(stdout);
    if (csv)
      std::fprintf(csv, "\"%s\",%.0f,%llu,%.4f,%.4f,%.2f\n", scene.name.c_str(), speed,
                   static_cast<unsigned long long>(frames), rate, notDrawn,
                   double(pass2) / double(frames));
  }
}

// 3. Frame time and work with and without culling, at several tessellation factors.
void frameCosts(vulkan::Context& context, const Scene& scene, const Options& o) {
  GpuScene g(context, scene);
  frame::RenderTarget target(context, o.width, o.height), plain(context, o.width, o.height);
  frame::Renderer renderer(context);
  const frame::CullMesh meshes[] = {g.mesh()};
  const frame::Camera start =
      frame::frameBounds(g.bounds, scene.viewDirection, scene.up, 40.0, o.width, o.height);
  const frame::PatchDraw draw{&g.gpu, &scene.patches, 0};
  for (uint32_t tess : {4u, 16u, 32u})
    for (bool allStages : {false, true})
      for (frame::CullDrawMode mode :
           {frame::CullDrawMode::Filtered, frame::CullDrawMode::TessFactorZero}) {
        progress("3. " + scene.name + ": tess " + std::to_string(tess) +
                 (allStages ? ", all stages, " : ", frustum + occlusion, ") + toString(mode));
        frame::CullFrameOptions co = cullOptions(o, scene, tess, allStages);
        co.drawMode = mode;
        frame::CullFrame cull(context, renderer, target, meshes, co);
        // The same frames in the diagnostic mode (a submission per pass) for the split.
        frame::CullFrameOptions diagnostic = co;
        diagnostic.timePasses = true;
        frame::RenderTarget diagnosticTarget(context, o.width, o.height);
        frame::CullFrame split(context, renderer, diagnosticTarget, meshes, diagnostic);
        std::vector<double> ratio, overhead, culledMs, plainMs;
        uint64_t tesCulled = 0, tesPlain = 0, fragCulled = 0, fragPlain = 0, culled = 0, total = 0;
        uint64_t tcsCulled = 0, tcsPlain = 0;
        renderer.render(plain, start, {&draw, 1}, g.occluders, co.render);  // JIT warm-up
        cull.render(start, g.occluders);
        split.render(start, g.occluders);
        const uint32_t frames = 12 * o.repeats;
        for (uint32_t f = 0; f < frames; ++f) {
          const auto cam = frame::orbit(start, g.bounds.center(), scene.up, 5.0 * f);
          const auto p = renderer.render(plain, cam, {&draw, 1}, g.occluders, co.render);
          const auto c = cull.render(cam, g.occluders);
          plainMs.push_back(p.wallMs);
          culledMs.push_back(c.totalMs());
          ratio.push_back(c.totalMs() / p.wallMs);
          const auto d = split.render(cam, g.occluders);
          overhead.push_back((d.pyramidMs + d.cullMs) / d.totalMs());
          tesPlain += p.statistics.tessEvaluationInvocations;
          tesCulled += c.pass1.tessEvaluationInvocations + c.pass2.tessEvaluationInvocations;
          fragPlain += p.statistics.fragmentShaderInvocations;
          tcsPlain += p.statistics.tessControlPatches;
          tcsCulled += c.pass1.tessControlPatches + c.pass2.tessControlPatches;
          fragCulled += c.pass1.fragmentShaderInvocations + c.pass2.fragmentShaderInvocations;
          culled += c.culled();
          total += c.patchesTotal;
        }
        std::printf(
            "| %s | %u | %s | %s | %.1f%% | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f%% |\n",
            scene.name.c_str(), tess, allStages ? "all" : "frustum + occlusion", toString(mode),
            100.0 * culled / total, median(plainMs), median(culledMs), median(ratio),
            double(tesCulled) / tesPlain, double(tcsCulled) / tcsPlain,
            double(fragCulled) / fragPlain, 100.0 * median(overhead));
        std::fflush(stdout);
      }
}

// 4. A long sequence with fast rotation (10 to 30 degrees per frame, changing direction):
// pixels covered without culling but not with it, and pixels that differ at all.
void sequence(vulkan::Context& context, const Scene& scene, const Options& o, bool aggressive,
              bool allStages) {
  GpuScene g(context, scene);
  frame::RenderTarget target(context, o.width, o.height), plain(context, o.width, o.height);
  frame::Renderer renderer(context);
  const frame::CullMesh meshes[] = {g.mesh()};
  frame::CullFrameOptions co = cullOptions(o, scene, 4, allStages);
  co.aggressive = aggressive;
  frame::CullFrame cull(context, renderer, target, meshes, co);
  frame::Camera cam =
      frame::frameBounds(g.bounds, scene.viewDirection, scene.up, 40.0, o.width, o.height);
  const frame::PatchDraw draw{&g.gpu, &scene.patches, 0};
  std::mt19937_64 rng(300);
  std::uniform_real_distribution<double> speed(10.0, 30.0);
  uint64_t uncovered = 0, different = 0, pixels = 0;
  uint32_t framesUncovered = 0, framesDifferent = 0, maxDifferent = 0;
  progress(std::string("4. ") + scene.name + (allStages ? ", all stages" : "") +
           (aggressive ? ", aggressive" : ", two-pass"));
  for (uint32_t f = 0; f < o.sequence; ++f) {
    const glm::dvec3 axis =
        (f / 50) % 2 ? scene.up : glm::dvec3(scene.up.z, scene.up.x, scene.up.y);
    cam = frame::orbit(cam, g.bounds.center(), axis, (f / 25) % 2 ? -speed(rng) : speed(rng));
    cull.render(cam, g.occluders);
    renderer.render(plain, cam, {&draw, 1}, g.occluders, co.render);
    const auto a = target.readItems(context), b = plain.readItems(context);
    const auto ca = target.readColor(context), cb = plain.readColor(context);
    uint32_t u = 0, d = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      u += b[i] != 0 && a[i] == 0;
      bool differs = a[i] != b[i];
      for (int c = 0; c < 4; ++c) differs = differs || ca[4 * i + c] != cb[4 * i + c];
      d += differs;
    }
    uncovered += u;
    different += d;
    pixels += a.size();
    framesUncovered += u > 0;
    framesDifferent += d > 0;
    maxDifferent = std::max(maxDifferent, d);
  }
  std::printf("| %s | %s | %u | %llu | %u | %llu | %u | %u | %.5f%% |\n", scene.name.c_str(),
              (std::string(allStages ? "all stages, " : "frustum + occlusion, ") +
               (aggressive ? "aggressive" : "two-pass"))
                  .c_str(),
              o.sequence, static_cast<unsigned long long>(uncovered), framesUncovered,
              static_cast<unsigned long long>(different), framesDifferent, maxDifferent,
              100.0 * different / pixels);
  std::fflush(stdout);
}

using osd_cull::bench::dataDir;

// 5. The first frame under each first-frame policy (averaged over whole-object views): what
// each pass draws and the tessellation work, against drawing everything once.
void firstFrames(vulkan::Context& context, const Scene& scene, const Options& o) {
  GpuScene g(context, scene);
  frame::RenderTarget target(context, o.width, o.height), plain(context, o.width, o.height);
  frame::Renderer renderer(context);
  const frame::CullMesh meshes[] = {g.mesh()};
  const frame::PatchDraw draw{&g.gpu, &scene.patches, 0};
  const uint32_t views = std::max(1u, std::min(o.views, 50u));
  for (frame::FirstFrame policy : {frame::FirstFrame::AllVisible, frame::FirstFrame::HalfVisible,
                                   frame::FirstFrame::NoneVisible}) {
    progress("5. " + scene.name + ": first frame " + toString(policy));
    frame::CullFrameOptions co = cullOptions(o, scene, 4);
    co.firstFrame = policy;
    frame::CullFrame cull(context, renderer, target, meshes, co);
    std::mt19937_64 rng(77);
    uint64_t pass1 = 0, pass2 = 0, tes = 0, tesPlain = 0, culled = 0;
    std::vector<double> ratio;
    cull.render(
        frame::frameBounds(g.bounds, scene.viewDirection, scene.up, 40.0, o.width, o.height),
        g.occluders);  // JIT warm-up
    for (uint32_t v = 0; v < views; ++v) {
      const glm::dvec3 dir = randomDirection(rng);
      const frame::Camera cam =
          frame::frameBounds(g.bounds, dir, upFor(dir, scene.up), 40.0, o.width, o.height);
      cull.reset(policy);
      const auto s = cull.render(cam, g.occluders);
      const auto p = renderer.render(plain, cam, {&draw, 1}, g.occluders, co.render);
      pass1 += s.drawnPass1;
      pass2 += s.drawnPass2;
      culled += s.culled();
      tes += s.pass1.tessEvaluationInvocations + s.pass2.tessEvaluationInvocations;
      tesPlain += p.statistics.tessEvaluationInvocations;
      ratio.push_back(s.totalMs() / p.wallMs);
    }
    std::printf("| %s | %s | %.0f | %.0f | %.0f | %.2f | %.2f |\n", scene.name.c_str(),
                toString(policy), double(pass1) / views, double(pass2) / views,
                double(culled) / views, double(tes) / tesPlain, median(ratio));
    std::fflush(stdout);
  }
}

// A vertex for Far::PrimvarRefiner.
struct RefinedPoint {
  glm::dvec3 p{0.0};
  void Clear() { p = glm::dvec3(0.0); }
  void AddWithWeight(const RefinedPoint& src, float weight) { p += double(weight) * src.p; }
};

// The paper's "1-4 split" (Niessner & Loop §6.2): the cage after one uniform Catmull-Clark
// step, as a new cage with the same limit surface. Only for cages without creases, corners
// or holes (BigGuy), whose tags would otherwise need carrying over.
CageMesh splitOnce(const CageMesh& cage) {
  if (!cage.creases.empty() || !cage.corners.empty() || !cage.holes.empty())
    throw Error("splitOnce: " + cage.source + " has tags; only plain cages are split");
  auto refiner = makeTopologyRefiner(cage);
  refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(1));
  std::vector<RefinedPoint> base(cage.positions.size());
  for (size_t i = 0; i < base.size(); ++i) base[i].p = cage.positions[i];
  const Far::TopologyLevel& level = refiner->GetLevel(1);
  std::vector<RefinedPoint> fine(static_cast<size_t>(level.GetNumVertices()));
  const RefinedPoint* src = base.data();
  RefinedPoint* dst = fine.data();
  Far::PrimvarRefiner(*refiner).Interpolate(1, src, dst);
  CageMesh out = cage;
  out.source = cage.source + " (split once)";
  out.positions.clear();
  for (const auto& v : fine) out.positions.push_back(v.p);
  out.faceSizes.clear();
  out.faceVertices.clear();
  for (int f = 0; f < level.GetNumFaces(); ++f) {
    const auto verts = level.GetFaceVertices(f);
    out.faceSizes.push_back(verts.size());
    for (int i = 0; i < verts.size(); ++i) out.faceVertices.push_back(verts[i]);
  }
  return out;
}

// `names`: comma-separated among default, bigguy0, bigguy1, bigguy2, ... (BigGuy at that
// isolation level) and bigguy-split (BigGuy split once, level 0: the paper's 1-4 split);
// BigGuy is skipped with a note when the data folder is missing.
std::vector<Scene> scenes(const std::string& names) {
  std::vector<Scene> out;
  std::stringstream list(names);
  std::string name;
  while (std::getline(list, name, ',')) {
    if (name == "default") {
      scene::Scene demo = scene::defaultScene();
      // Closed cages with outward normals (scene/procedural.h), walls as occluders.
      out.push_back({"default scene",
                     std::move(demo.patches),
                     std::move(demo.occluders),
                     demo.up,
                     demo.viewDirection,
                     {true, "built-in scene: closed, outward cages"}});
    } else if (name.rfind("bigguy", 0) == 0 && (name.size() == 7 || name == "bigguy-split")) {
      const auto path = dataDir() / "characters" / "bigguy.obj";
      if (!std::filesystem::exists(path)) {
        std::printf("(%s skipped: %s not found)\n", name.c_str(), path.string().c_str());
        continue;
      }
      const bool split = name == "bigguy-split";
      PatchOptions options;
      options.isolationLevel = split ? 0 : name[6] - '0';
      const CageMesh cage = split ? splitOnce(adapters::loadCage(path)) : adapters::loadCage(path);
      bound::CullablePatches c = bound::cullablePatches(cage, options);
      Scene s{split ? std::string("BigGuy split once, level 0") : "BigGuy level " + name.substr(6),
              std::move(c.extraction.patches),
              {},
              {0, 1, 0},
              {0.3, 0.25, 1.0},
              std::move(c.backPatch)};
      out.push_back(std::move(s));
    } else {
      throw Error("--scenes: unknown scene '" + name + "'");
    }
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::run("bench-occlusion", [&] {
    Options o;
    if (!parse(argc, argv, o)) return 0;
    vulkan::Context context(bench::contextOptions(o.device));
    const std::vector<Scene> all = scenes(o.scenes);
    std::printf(
        "device: %s; image %ux%u; Hi-Z top level at half resolution; back faces %s, the same "
        "with and without culling\n\n",
        context.info().name.c_str(), o.width, o.height,
        o.drawBackFaces ? "drawn" : "culled by the rasterizer on closed, oriented scenes");
    for (const Scene& s : all) {
      const bool culled = s.validity.enabled && !o.drawBackFaces;
      const std::string why = o.drawBackFaces ? "--draw-back-faces" : s.validity.reason;
      std::printf("- %s: back faces %s\n", s.name.c_str(),
                  culled ? "culled on both sides" : ("drawn on both sides (" + why + ")").c_str());
    }
    std::printf("\n");
    auto want = [&](char c) { return o.only.find(c) != std::string::npos; };
    if (want('1')) {
      std::printf("## Occlusion cull rate, whole-object views\n\n");
      std::printf(
          "| scene | patches | views | occlusion cull rate | with tight lookup | all stages | "
          "oracle rate |\n");
      std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
      for (const Scene& s : all) cullRates(context, s, o);
    }
    if (want('2')) {
      std::printf("\n## Cull rate against rotation speed (orbit of %.0f degrees)\n\n",
                  o.orbitDegrees);
      std::printf(
          "| scene | degrees / frame | frames | occlusion cull rate | not drawn in the frame | "
          "patches drawn in pass 2 |\n");
      std::printf("|---|---:|---:|---:|---:|---:|\n");
      const bench::CsvFile csv =
          bench::openCsv(o.csv,
                         "scene,degrees_per_frame,frames,occlusion_cull_rate_percent,"
                         "not_drawn_percent,pass2_patches_per_frame");
      for (const Scene& s : all) rotationRates(context, s, o, csv.get());
    }
    if (want('3')) {
      std::printf("\n## Frame cost with and without culling (medians over %u frames)\n\n",
                  12 * o.repeats);
      std::printf(
          "| scene | tess | stages | draw mode | culled | frame ms, no culling | frame ms, culling "
          "| time ratio | TES ratio | TCS patch ratio | fragment ratio | pyramid + cull share |\n");
      std::printf("|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
      for (const Scene& s : all) frameCosts(context, s, o);
    }
    if (want('5')) {
      std::printf("\n## First frame by first-frame policy (means over %u views)\n\n",
                  std::max(1u, std::min(o.views, 50u)));
      std::printf(
          "| scene | policy | drawn pass 1 | drawn pass 2 | culled | TES ratio | time ratio |\n");
      std::printf("|---|---|---:|---:|---:|---:|---:|\n");
      for (const Scene& s : all) firstFrames(context, s, o);
    }
    if (want('4')) {
      std::printf("\n## Image equality over a fast-rotation sequence\n\n");
      std::printf(
          "| scene | mode | frames | uncovered pixels | frames with uncovered | differing pixels | "
          "frames with differences | max differing / frame | differing share |\n");
      std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
      for (const Scene& s : all) {
        sequence(context, s, o, false, false);
        sequence(context, s, o, false, true);
        sequence(context, s, o, true, true);
      }
    }
    progress("done");
    return 0;
  });
}
