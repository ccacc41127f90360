// bench-frame-cost: what culling costs and saves in a whole frame, like for like, for
// docs/results/frame-cost.md. Prints Markdown tables:
//  P. the Hi-Z pyramid build at the image size: each build in its own submission,
//     interleaved, medians, against the floor (a plain single-threaded C++ loop building the
//     same 2x2 max chain from a depth array of the image's size, timed in the same run) with
//     the ratio build / floor; with an empty submission and the unculled tess-4 frame;
//  F. per camera path and tessellation level, per cull configuration (frustum; frustum +
//     back-patch, the tangent plane; frustum + NCONE; frustum + Hi-Z occlusion; all three,
//     with the tangent plane; each with the per-patch boxes the library precomputes for a
//     static mesh, CullSettings::staticPoints): x (share of patches not drawn),
//     the three sides unculled U, free culling F (the same frame drawing exactly the
//     patches the culled frame drew, in one pass from lists prepared on the host, no cull,
//     pyramid or status work: DESIGN.md) and culled C, the overhead (C - F) / U, the share
//     of the free saving (U - C) / (U - F), the ratio C / U, TES and fragment-invocation
//     ratios, the culled frame's GPU time per stage from timestamps in its one submission,
//     pass 2's time beyond its share of the drawing (its TES share of both passes' time),
//     and GPU / wall of the culled frame (timestamps against the host clock);
//     (rows "aN": screen-space adaptive levels, N pixels per segment, after the uniform ones);
//  B. the break-even uniform tessellation level per configuration and path.
// Every table ends with the load average and the peak RSS.
//
//   bench-frame-cost [--width 1280] [--height 720] [--tess 1,4,8,16,32] [--adaptive 4,8,16]
//                    [--frames 8] [--orbit-step 3]
//                    [--paths default-orbit,default-walk,bigguy-orbit,bigguy-closeup]
//                    [--bigguy-level 2] [--only PFB] [--repeats 20] [--csv FILE]
//                    [--device X]
//
// Both sides of every ratio run the same RenderOptions: the same tessellation, image and
// camera, and back faces culled by the rasterizer where the mesh is closed and oriented.
// The unculled frame is Renderer::render (one submission); the culled frame is
// CullFrame::render (one submission) with occlusion, frame::renderCulled (cull dispatch and
// draws in one submission) without; the free frame is FreeCullingFrame::render (one
// submission). Per camera the sides run in a rotated order (the unculled frame, then each
// configuration's culled and free frames), so that no side always follows the heavy ones.
// Progress goes to stderr.
#include "bench_support.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/free_culling_frame.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/query.h"

#include <glm/trigonometric.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace osd_cull;
using osd_cull::bench::median;

struct Options {
  uint32_t width = 1280, height = 720, frames = 8, repeats = 20, bigguyLevel = 2;
  std::vector<uint32_t> tess = {1, 4, 8, 16, 32};
  std::vector<uint32_t> adaptive;  // pixels per segment
  std::string paths = "default-orbit,default-walk,bigguy-orbit,bigguy-closeup";
  std::string only = "PFB";
  std::string csv, device;
  // Degrees the orbit paths turn per frame (0: the whole circle over --frames, frames far
  // apart): a renderer's camera moves a few degrees a frame, and the two-pass frame carries
  // the visibility of the previous one.
  double orbitStep = 3.0;
};

using osd_cull::bench::nameList;
using osd_cull::bench::progress;

// False after --help.
bool parse(int argc, char** argv, Options& o) {
  return bench::CommandLine("bench-frame-cost", "bench_frame_cost.cpp")
      .imageAndDevice(o.width, o.height, o.repeats, o.device)
      .number("--frames", o.frames, 1)
      .real("--orbit-step", o.orbitStep, 0.0)
      .number("--bigguy-level", o.bigguyLevel)
      .numbers("--tess", o.tess)
      .numbers("--adaptive", o.adaptive)
      .text("--paths", o.paths)
      .text("--only", o.only)
      .text("--csv", o.csv)
      .parse(argc, argv);
}

// A mesh with occluders on the device, and how to cull it.
struct Scene {
  std::string name;
  PatchSet patches;
  std::vector<frame::TriangleMesh> occluders;
  glm::dvec3 up{0, 0, 1}, viewDirection{0, 0, 1};
  bound::BackPatchValidity validity;
};

Scene defaultScene() {
  scene::Scene s = scene::defaultScene();
  return {"built-in scene",       std::move(s.patches),
          std::move(s.occluders), s.up,
          s.viewDirection,        {true, "built-in scene: closed, outward cages"}};
}

Scene bigGuy(uint32_t level) {
  bench::CullMesh m = bench::loadCullMesh(bench::dataDir() / "characters" / "bigguy.obj", level);
  return {"BigGuy level " + std::to_string(level),
          std::move(m.patches),
          {},
          {0, 1, 0},
          {0.3, 0.25, 1.0},
          m.validity};
}

// A camera path: `frames` cameras.
using Path = std::function<frame::Camera(uint32_t frame)>;

// An orbit around the scene's bounds from the distance that frames them at 40 degrees; a
// narrower field of view (a close-up: parts of the scene off screen) keeps the eye there,
// outside the bounding sphere. Frame f is at 7 + f * --orbit-step degrees (the warm-up
// frame at frame 0's camera).
Path orbitPath(const Scene& s, const Options& o, double fovyDegrees) {
  const frame::Bounds b = frame::boundsOf(s.patches.points);
  const frame::Camera framed =
      frame::frameBounds(b, s.viewDirection, s.up, 40.0, o.width, o.height);
  const double d = glm::distance(framed.eye(), b.center()), r = b.radius();
  const frame::Camera start =
      frame::Camera::lookAt(framed.eye(), b.center(), s.up, fovyDegrees, o.width, o.height,
                            std::max(d - 1.5 * r, d * 1e-3), d + 1.5 * r);
  const double step = o.orbitStep > 0.0 ? o.orbitStep : 360.0 / o.frames;
  return [=](uint32_t f) { return frame::orbit(start, b.center(), s.up, step * f + 7.0); };
}

// A walk at eye height through the built-in scene (z up, floor at z = -1), turning from
// looking along +x to looking along +y: objects enter and leave the view.
Path walkPath(const Options& o) {
  return [=](uint32_t f) {
    const double t = o.frames > 1 ? double(f) / double(o.frames - 1) : 0.0;
    const glm::dvec3 eye(-3.2 + 5.0 * t, -2.6 + 2.2 * t, -0.3);
    const double a = glm::radians(20.0 + 70.0 * t);
    const glm::dvec3 ahead(std::cos(a), std::sin(a), -0.05);
    return frame::Camera::lookAt(eye, eye + ahead, {0, 0, 1}, 60.0, o.width, o.height, 0.02, 20.0);
  };
}

// One cull configuration of the frame.
struct Config {
  std::string name;
  std::string backPatch;  // the back-patch method, or none
  bool occlusion = false;
};
const Config kConfigs[] = {{"frustum", "", false},
                           {"frustum + back-patch", "tangent-plane", false},
                           {"frustum + ncone", "ncone", false},
                           {"frustum + occlusion", "", true},
                           {"all", "tangent-plane", true}};

// The settings the library runs for a static mesh (session::MeshSession): the precomputed
// per-patch boxes (CullSettings::staticPoints; used where there is no occlusion stage).
frame::CullSettings settings(const Config& c, const Scene& s) {
  frame::CullSettings settings{true, c.backPatch, c.occlusion ? "hiz" : "", s.validity};
  settings.staticPoints = true;
  return settings;
}

// Per configuration and tessellation level, over the frames of one path: wall times of
// the three sides (unculled, free culling, culled), the culled frame's GPU stage times.
struct Row {
  std::vector<double> plain, free, culled, ratio;
  std::vector<double> pass1, pyramid, cull, pass2, gpuTotal, pass2Excess;
  uint64_t notDrawn = 0, total = 0, tes = 0, freeTes = 0, fragments = 0, frustum = 0;
};

struct PathResult {
  std::string name;
  std::map<std::pair<std::string, size_t>, Row> rows;          // (level label, config)
  std::map<std::string, std::pair<uint64_t, uint64_t>> plain;  // level -> TES, fragments
};

// The configurations' frames at one tessellation level: a CullFrame with occlusion, else a
// CullPass drawn by renderCulled.
struct ConfigFrames {
  std::vector<std::unique_ptr<frame::CullFrame>> frames;
  std::vector<std::unique_ptr<frame::CullPass>> passes;
};

ConfigFrames makeConfigFrames(vulkan::Context& context, frame::Renderer& renderer,
                              frame::RenderTarget& target, frame::GpuPatchSet& gpu,
                              const Scene& scene, const frame::RenderOptions& render) {
  ConfigFrames f;
  const frame::CullMesh cullMeshes[] = {{&gpu, &scene.patches}};
  for (const Config& c : kConfigs) {
    frame::CullFrameOptions fo;
    fo.render = render;
    fo.cull = settings(c, scene);
    f.frames.push_back(
        c.occlusion ? std::make_unique<frame::CullFrame>(context, renderer, target, cullMeshes, fo)
                    : nullptr);
    f.passes.push_back(
        c.occlusion ? nullptr
                    : std::make_unique<frame::CullPass>(context, gpu, scene.patches, fo.cull));
  }
  return f;
}

// The culled frame of configuration `c` (one submission), the patches it drew, and into
// `row` its GPU stage times.
struct Culled {
  double ms = 0;
  std::vector<uint32_t> drawn;
  uint32_t frustum = 0;
  vulkan::PipelineStatistics statistics;
};

Culled culledFrame(vulkan::Context& context, frame::Renderer& renderer, frame::RenderTarget& target,
                   ConfigFrames& configs, size_t c, const frame::Camera& cam,
                   std::span<const frame::GpuTriangleMesh* const> occluders,
                   const frame::RenderOptions& render, Row& row, bool timed) {
  Culled r;
  if (frame::CullFrame* cf = configs.frames[c].get()) {
    const std::vector<uint32_t> before = cf->visibility(0).readStatus(context);
    const frame::CullFrameStats s = cf->render(cam, occluders);
    r.ms = s.frameMs;
    r.drawn = frame::patchesDrawnByFrame(before, cf->visibility(0).readStatus(context), false);
    r.frustum = s.culledFrustum;
    r.statistics = s.pass1;
    r.statistics += s.pass2;
    if (timed && s.gpu.measured()) {
      row.pass1.push_back(s.gpu.pass1);
      row.pyramid.push_back(s.gpu.pyramid);
      row.cull.push_back(s.gpu.cull);
      row.pass2.push_back(s.gpu.pass2);
      row.gpuTotal.push_back(s.gpu.total / s.frameMs);
      // Pass 2's share of the drawing: its share of the TES work times both passes' time.
      const double tes = double(r.statistics.tessEvaluationInvocations);
      const double share = tes > 0 ? double(s.pass2.tessEvaluationInvocations) / tes : 0.0;
      row.pass2Excess.push_back(s.gpu.pass2 - share * (s.gpu.pass1 + s.gpu.pass2));
    }
    return r;
  }
  frame::CullPass& pass = *configs.passes[c];
  const frame::FrameStats s = frame::renderCulled(renderer, target, cam, pass, occluders, render);
  r.ms = s.wallMs;
  r.statistics = s.statistics;
  const auto results = pass.results();
  for (uint32_t p = 0; p < results.size(); ++p) {
    const uint32_t stage = bound::CullCode{results[p]}.stage();
    if (stage == shader::kStageNone) r.drawn.push_back(p);
    r.frustum += stage == shader::kStageFrustum;
  }
  if (timed) {
    row.cull.push_back(pass.run(cam, render.tessellation));
    if (s.gpuMs > 0) row.gpuTotal.push_back(s.gpuMs / s.wallMs);
  }
  return r;
}

PathResult measurePath(vulkan::Context& context, const std::string& name, const Scene& scene,
                       const Path& path, const Options& o) {
  PathResult result{name, {}, {}};
  frame::GpuPatchSet gpu(context, scene.patches);
  std::vector<frame::GpuTriangleMesh> meshes;
  for (const auto& m : scene.occluders) meshes.emplace_back(context, m);
  std::vector<const frame::GpuTriangleMesh*> occluders;
  for (const auto& m : meshes) occluders.push_back(&m);
  frame::Renderer renderer(context);
  frame::RenderTarget plain(context, o.width, o.height), culled(context, o.width, o.height),
      freeTarget(context, o.width, o.height);
  const frame::PatchDraw draw{&gpu, &scene.patches, 0};
  frame::FreeCullingFrame freeFrame(context, renderer, {&draw, 1});
  const size_t sides = 1 + std::size(kConfigs);  // the unculled frame, then each config
  for (const auto& [tess, tessellation] : bench::tessellationLevels(
           o.tess, o.adaptive, context.info().limits.maxTessellationGenerationLevel)) {
    progress("F. " + name + ": tess " + tess);
    frame::RenderOptions render;
    render.tessellation = tessellation;
    render.cullBackFaces = scene.validity.enabled;
    ConfigFrames configs = makeConfigFrames(context, renderer, culled, gpu, scene, render);
    uint64_t plainTes = 0, plainFragments = 0;
    // Frame -1 warms up (pipelines; temporal status at the path's first camera).
    for (int f = -1; f < int(o.frames); ++f) {
      const frame::Camera cam = path(uint32_t(std::max(f, 0)));
      const bool timed = f >= 0;
      double plainMs = 0;
      std::vector<std::pair<double, double>> sideMs(std::size(kConfigs));  // culled, free
      std::vector<Culled> results(std::size(kConfigs));
      // The sides in a rotated order per camera: each one runs first, after the unculled
      // frame and after the heavy ones in turn (a configuration's free frame follows its
      // culled frame, whose drawn patches it draws).
      for (size_t k = 0; k < sides; ++k) {
        const size_t side = (k + size_t(std::max(f, 0))) % sides;
        if (side == 0) {
          const frame::FrameStats p = renderer.render(plain, cam, {&draw, 1}, occluders, render);
          plainMs = p.wallMs;
          if (timed) {
            plainTes += p.statistics.tessEvaluationInvocations;
            plainFragments += p.statistics.fragmentShaderInvocations;
          }
          continue;
        }
        const size_t c = side - 1;
        Row& row = result.rows[{tess, c}];
        results[c] =
            culledFrame(context, renderer, culled, configs, c, cam, occluders, render, row, timed);
        freeFrame.setPatches(0, results[c].drawn);
        const frame::FrameStats fs = freeFrame.render(freeTarget, cam, occluders, render);
        sideMs[c] = {results[c].ms, fs.wallMs};
        if (timed) row.freeTes += fs.statistics.tessEvaluationInvocations;
      }
      if (!timed) continue;
      for (size_t c = 0; c < std::size(kConfigs); ++c) {
        Row& row = result.rows[{tess, c}];
        const Culled& r = results[c];
        row.plain.push_back(plainMs);
        row.culled.push_back(sideMs[c].first);
        row.free.push_back(sideMs[c].second);
        row.ratio.push_back(sideMs[c].first / plainMs);
        row.notDrawn += scene.patches.patchCount() - r.drawn.size();
        row.total += scene.patches.patchCount();
        row.tes += r.statistics.tessEvaluationInvocations;
        row.fragments += r.statistics.fragmentShaderInvocations;
        row.frustum += r.frustum;
      }
    }
    result.plain[tess] = {plainTes, plainFragments};
  }
  return result;
}

// "a / b / c / d" of medians, "-" for an empty series.
std::string medians(std::initializer_list<const std::vector<double>*> series) {
  std::string text;
  for (const auto* v : series) {
    char one[32];
    std::snprintf(one, sizeof one, "%.2f", median(*v));
    text += (text.empty() ? "" : " / ") + (v->empty() ? std::string("-") : std::string(one));
  }
  return text;
}

void printPath(const PathResult& r, const Options& o, FILE* csv) {
  std::printf("\n### %s\n\n", r.name.c_str());
  std::printf(
      "| tess | stages | x (not drawn) | frustum culled | ms unculled | ms free | ms culled | "
      "overhead (C-F)/U | share of free saving (U-C)/(U-F) | ratio C/U | TES ratio | free TES = "
      "culled | fragment ratio | GPU ms: pass 1 / pyramid / cull / pass 2 | pass 2 - its share, "
      "ms | GPU / wall |\n");
  std::printf("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---|---:|---:|\n");
  for (const auto& [tess, tessellation] : bench::tessellationLevels(o.tess, o.adaptive, 64))
    for (size_t c = 0; c < std::size(kConfigs); ++c) {
      const Row& row = r.rows.at({tess, c});
      const double x = double(row.notDrawn) / double(row.total);
      const double u = median(row.plain), fr = median(row.free), cu = median(row.culled);
      const auto [tes, fragments] = r.plain.at(tess);
      const double overhead = (cu - fr) / u;
      // The free saving is too small to divide by where the free frame is within 2% of the
      // unculled one.
      const bool shareValid = u - fr > 0.02 * u;
      const double share = shareValid ? (u - cu) / (u - fr) : 0.0;
      char shareText[32] = "-";
      if (shareValid) std::snprintf(shareText, sizeof shareText, "%.0f%%", 100 * share);
      const std::string split = kConfigs[c].occlusion
                                    ? medians({&row.pass1, &row.pyramid, &row.cull, &row.pass2})
                                    : "cull " + medians({&row.cull}) + " (own run)";
      const std::string excess = kConfigs[c].occlusion ? medians({&row.pass2Excess}) : "-";
      std::printf(
          "| %s | %s | %.1f%% | %.1f%% | %.2f | %.2f | %.2f | %.1f%% | %s | %.2f | %.2f | %s | "
          "%.2f | %s | %s | %s |\n",
          tess.c_str(), kConfigs[c].name.c_str(), 100 * x,
          100.0 * double(row.frustum) / double(row.total), u, fr, cu, 100 * overhead, shareText,
          median(row.ratio), double(row.tes) / double(tes), row.freeTes == row.tes ? "yes" : "NO",
          double(row.fragments) / double(fragments), split.c_str(), excess.c_str(),
          medians({&row.gpuTotal}).c_str());
      if (csv)
        std::fprintf(csv,
                     "\"%s\",\"%s\",%s,%.5f,%.3f,%.3f,%.3f,%.5f,%.5f,%.5f,%.5f,%.5f,%.3f,%.3f,%.3f,"
                     "%.3f,%.3f\n",
                     r.name.c_str(), kConfigs[c].name.c_str(), tess.c_str(), x, u, fr, cu, overhead,
                     shareValid ? share : std::nan(""), median(row.ratio),
                     double(row.tes) / double(tes), double(row.fragments) / double(fragments),
                     median(row.pass1), median(row.pyramid), median(row.cull), median(row.pass2),
                     median(row.pass2Excess));
    }
  std::printf("\n%s\n", bench::machineState().c_str());
  std::fflush(stdout);
  if (csv) std::fflush(csv);
}

// The lowest level from which on every measured level has a median ratio below 1.
void printBreakEven(const std::vector<PathResult>& results, const Options& o) {
  std::printf("\n## Break-even tessellation level (ratio < 1 from this level on)\n\n| path |");
  for (const Config& c : kConfigs) std::printf(" %s |", c.name.c_str());
  std::printf("\n|---|---|---|---|---|\n");
  for (const PathResult& r : results) {
    std::printf("| %s |", r.name.c_str());
    for (size_t c = 0; c < std::size(kConfigs); ++c) {
      std::string level = "never";
      for (auto t = o.tess.rbegin(); t != o.tess.rend(); ++t) {
        if (median(r.rows.at({std::to_string(*t), c}).ratio) >= 1.0) break;
        level = std::to_string(*t);
      }
      std::printf(" %s |", level.c_str());
    }
    std::printf("\n");
  }
}

double timed(const std::function<void()>& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// The floor of a pyramid build (DESIGN.md, "Floors"): a plain single-threaded loop building
// the same chain of 2x2 maxima (level 0 at half resolution, pixels past the image far,
// texels wholly in the padding skipped as the GPU build's later builds skip them) from a
// depth array of the image's size. Returns the levels, the covered texels of each.
struct FloorLevel {
  uint32_t width = 0, height = 0;
  std::vector<float> texels;
};

std::vector<FloorLevel> floorMaxChain(const std::vector<float>& depth,
                                      const bound::HiZLayout& layout) {
  std::vector<FloorLevel> levels(layout.levelCount);
  const uint32_t s = layout.baseShift, n = 1u << s;
  auto covered = [&](uint32_t pixels, uint32_t level) {
    return std::max(1u, (pixels + (1u << (level + s)) - 1) >> (level + s));
  };
  FloorLevel& l0 = levels[0];
  l0.width = std::min(layout.levelWidth(0), covered(layout.width, 0));
  l0.height = std::min(layout.levelHeight(0), covered(layout.height, 0));
  l0.texels.assign(size_t{l0.width} * l0.height, 1.0f);
  if (s == 1) {
    // The paper's half resolution: each texel the maximum of a 2x2 pixel block, the inner
    // loop over whole blocks without branches (the edges below).
    const uint32_t w = layout.width, fullX = w / 2;
    for (uint32_t ty = 0; ty < layout.height / 2; ++ty) {
      const float* r0 = depth.data() + size_t{2 * ty} * w;
      const float* r1 = r0 + w;
      float* dst = l0.texels.data() + size_t{ty} * l0.width;
      for (uint32_t tx = 0; tx < fullX; ++tx)
        dst[tx] =
            std::max(std::max(r0[2 * tx], r0[2 * tx + 1]), std::max(r1[2 * tx], r1[2 * tx + 1]));
    }
  } else {
    for (uint32_t y = 0; y < layout.height; ++y) {
      const float* row = depth.data() + size_t{y} * layout.width;
      float* dst = l0.texels.data() + size_t{y >> s} * l0.width;
      for (uint32_t x = 0; x < layout.width; ++x) {
        float& t = dst[x >> s];
        t = (y % n == 0 && x % n == 0) ? row[x] : std::max(t, row[x]);
      }
    }
  }
  // A footprint cut by the image's right or bottom edge includes far padding.
  if (layout.width % n)
    for (uint32_t y = 0; y < l0.height; ++y) l0.texels[size_t{y} * l0.width + l0.width - 1] = 1.0f;
  if (layout.height % n)
    for (uint32_t x = 0; x < l0.width; ++x) l0.texels[size_t{l0.height - 1} * l0.width + x] = 1.0f;
  for (uint32_t l = 1; l < layout.levelCount; ++l) {
    const FloorLevel& src = levels[l - 1];
    FloorLevel& dst = levels[l];
    dst.width = std::min(layout.levelWidth(l), covered(layout.width, l));
    dst.height = std::min(layout.levelHeight(l), covered(layout.height, l));
    dst.texels.resize(size_t{dst.width} * dst.height);
    for (uint32_t y = 0; y < dst.height; ++y)
      for (uint32_t x = 0; x < dst.width; ++x) {
        // Sources past the covered part are padding: far.
        auto at = [&](uint32_t sx, uint32_t sy) {
          return sx < src.width && sy < src.height ? src.texels[size_t{sy} * src.width + sx] : 1.0f;
        };
        const uint32_t sx = 2 * x, sy = 2 * y;
        if (sx + 1 < src.width && sy + 1 < src.height) {  // inside: all four
          const float* a = src.texels.data() + size_t{sy} * src.width + sx;
          dst.texels[size_t{y} * dst.width + x] =
              std::max(std::max(a[0], a[1]), std::max(a[src.width], a[src.width + 1]));
          continue;
        }
        const bool x1 = sx + 1 < layout.levelWidth(l - 1), y1 = sy + 1 < layout.levelHeight(l - 1);
        float m = at(sx, sy);
        if (x1) m = std::max(m, at(sx + 1, sy));
        if (y1) m = std::max(m, at(sx, sy + 1));
        if (x1 && y1) m = std::max(m, at(sx + 1, sy + 1));
        dst.texels[size_t{y} * dst.width + x] = m;
      }
  }
  return levels;
}

// True when every covered texel of the floor's levels equals the GPU pyramid's.
bool floorEqualsBuild(const std::vector<FloorLevel>& floor,
                      const std::vector<std::vector<float>>& built,
                      const bound::HiZLayout& layout) {
  for (uint32_t l = 0; l < floor.size(); ++l)
    for (uint32_t y = 0; y < floor[l].height; ++y)
      for (uint32_t x = 0; x < floor[l].width; ++x)
        if (floor[l].texels[size_t{y} * floor[l].width + x] !=
            built[l][size_t{y} * layout.levelWidth(l) + x])
          return false;
  return true;
}

// P. The pyramid builds over the depth of a rendered built-in scene frame.
void pyramidCost(vulkan::Context& context, const Options& o) {
  const Scene scene = defaultScene();
  frame::GpuPatchSet gpu(context, scene.patches);
  frame::Renderer renderer(context);
  frame::RenderTarget target(context, o.width, o.height);
  frame::RenderOptions render;
  render.tessellation.uniformLevel = 4;
  render.cullBackFaces = true;
  const frame::Camera cam = orbitPath(scene, o, 40.0)(0);
  const frame::PatchDraw draw{&gpu, &scene.patches, 0};
  std::vector<double> frameMs, emptyMs;
  for (int i = 0; i < 3; ++i) renderer.render(target, cam, {&draw, 1}, {}, render);
  struct Kind {
    std::string name;
    frame::HiZReduction reduction;
    bool legacy = false;
    bool readDepthImage = false;
  };
  std::vector<Kind> kinds = {{"blocked: 3 levels a dispatch, depth copied to RGBA rows (default)",
                              frame::HiZReduction::Blocked},
                             {"blocked, top level gathered from the depth image",
                              frame::HiZReduction::Blocked, false, true},
                             {"single pass (1 dispatch)", frame::HiZReduction::SinglePass},
                             {"per level, four-tap", frame::HiZReduction::FourTap},
                             {"per level, four-tap, before (every texel every build)",
                              frame::HiZReduction::FourTap, true}};
  if (frame::supportsMinmaxReduction(context)) {
    kinds.push_back(
        {"per level, min/max sampler, gathered top level", frame::HiZReduction::Sampler});
    kinds.push_back({"per level, min/max sampler, before (four-tap top level, every texel)",
                     frame::HiZReduction::Sampler, true});
  }
  std::vector<std::unique_ptr<frame::HiZPyramid>> pyramids;
  std::vector<double> createMs;
  for (const auto& k : kinds) {
    frame::HiZOptions ho;
    ho.reduction = k.reduction;
    ho.legacyBuild = k.legacy;
    ho.readDepthImage = k.readDepthImage;
    createMs.push_back(timed([&] {
      pyramids.push_back(std::make_unique<frame::HiZPyramid>(context, target.depth(), ho));
      pyramids.back()->build(context, frame::RenderTarget::kDepthLayout);
    }));
  }
  const auto& layout = pyramids[0]->layout();
  const std::vector<float> depth = target.readDepth(context);
  std::optional<vulkan::TimestampQuery> stamps;
  if (vulkan::TimestampQuery::unavailableReason(context).empty()) stamps.emplace(context, 2);
  // One build in its own submission: wall ms, and GPU ms between timestamps around it.
  auto build = [&](frame::HiZPyramid& pyramid) {
    double gpuMs = std::nan("");
    const double wall = timed([&] {
      context.submit([&](VkCommandBuffer cmd) {
        if (stamps) {
          stamps->reset(cmd);
          stamps->write(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
        }
        pyramid.record(cmd, frame::RenderTarget::kDepthLayout);
        if (stamps) stamps->write(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 1);
      });
    });
    if (stamps) gpuMs = stamps->elapsedMs(0, 1);
    return std::pair(wall, gpuMs);
  };
  std::vector<std::vector<double>> ms(kinds.size()), gpuMs(kinds.size());
  std::vector<double> floorMs;
  std::vector<FloorLevel> floor;
  for (uint32_t r = 0; r < o.repeats; ++r) {
    // Rotated: each build runs after the frame, the floor and the others in turn.
    const size_t sides = kinds.size() + 2;
    for (size_t k = 0; k < sides; ++k) {
      const size_t side = (k + r) % sides;
      if (side == kinds.size())
        frameMs.push_back(renderer.render(target, cam, {&draw, 1}, {}, render).wallMs);
      else if (side == kinds.size() + 1)
        floorMs.push_back(timed([&] { floor = floorMaxChain(depth, layout); }));
      else {
        const auto [wall, gpuBuildMs] = build(*pyramids[side]);
        ms[side].push_back(wall);
        if (!std::isnan(gpuBuildMs)) gpuMs[side].push_back(gpuBuildMs);
      }
    }
    emptyMs.push_back(timed([&] { context.submit([](VkCommandBuffer) {}); }));
  }
  // The same values: the floor does the build's arithmetic (the scene has not moved).
  renderer.render(target, cam, {&draw, 1}, {}, render);
  const bool same = floorEqualsBuild(floorMaxChain(target.readDepth(context), layout),
                                     pyramids[0]->readLevels(context), layout);
  std::printf(
      "## Hi-Z pyramid build, %ux%u (%u levels from %ux%u), medians over %u interleaved "
      "repeats, each a submission and wait\n\n",
      o.width, o.height, layout.levelCount, layout.levelWidth(0), layout.levelHeight(0), o.repeats);
  std::printf(
      "| build | dispatches | ms (wall) | GPU ms (timestamps) | GPU / floor | share of the "
      "unculled tess-4 frame | first build incl. pipeline creation, ms |\n"
      "|---|---:|---:|---:|---:|---:|---:|\n");
  const double frame = median(frameMs), floorMedian = median(floorMs);
  for (size_t k = 0; k < kinds.size(); ++k)
    std::printf("| %s | %u | %.2f | %.2f | %.1fx | %.1f%% | %.0f |\n", kinds[k].name.c_str(),
                pyramids[k]->dispatchCount(), median(ms[k]), median(gpuMs[k]),
                median(gpuMs[k]) / floorMedian, 100 * median(ms[k]) / frame, createMs[k]);
  std::printf(
      "| floor: plain C++ 2x2 max chain, 1 thread (values equal the build: %s) | 0 | "
      "%.2f | | 1.0x | %.1f%% | |\n",
      same ? "yes" : "NO", floorMedian, 100 * floorMedian / frame);
  std::printf("| (empty submission) | 0 | %.2f | | | %.1f%% | |\n", median(emptyMs),
              100 * median(emptyMs) / frame);
  std::printf("\nUnculled built-in scene frame, tess 4, back faces culled: %.2f ms (median). %s\n",
              frame, bench::machineState().c_str());
  if (!stamps)
    std::printf("No GPU times: %s\n", vulkan::TimestampQuery::unavailableReason(context).c_str());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  return bench::run("bench-frame-cost", [&] {
    Options o;
    if (!parse(argc, argv, o)) return 0;
    vulkan::Context context(bench::contextOptions(o.device));
    std::printf("bench-frame-cost: %s, %ux%u\n\n", context.info().name.c_str(), o.width, o.height);
    auto want = [&](char c) { return o.only.find(c) != std::string::npos; };
    if (want('P')) pyramidCost(context, o);
    if (!want('F') && !want('B')) return 0;
    const bench::CsvFile csv =
        bench::openCsv(o.csv,
                       "path,stages,tess,not_drawn,unculled_ms,free_ms,culled_ms,overhead,"
                       "share_of_free_saving,ratio,tes_ratio,fragment_ratio,gpu_pass1_ms,"
                       "gpu_pyramid_ms,gpu_cull_ms,gpu_pass2_ms,pass2_excess_ms");
    std::printf(
        "\n## Frame cost, culled / unculled, like for like (medians over %u frames per "
        "level)\n",
        o.frames);
    std::vector<PathResult> results;
    std::unique_ptr<Scene> builtIn, guy;
    for (const std::string& p : nameList(o.paths)) {
      if (p.rfind("default", 0) == 0 && !builtIn) builtIn = std::make_unique<Scene>(defaultScene());
      if (p.rfind("bigguy", 0) == 0 && !guy) guy = std::make_unique<Scene>(bigGuy(o.bigguyLevel));
      if (p == "default-orbit")
        results.push_back(measurePath(context, "built-in scene, orbit", *builtIn,
                                      orbitPath(*builtIn, o, 40.0), o));
      else if (p == "default-walk")
        results.push_back(measurePath(context, "built-in scene, walk", *builtIn, walkPath(o), o));
      else if (p == "bigguy-orbit")
        results.push_back(
            measurePath(context, guy->name + ", orbit", *guy, orbitPath(*guy, o, 40.0), o));
      else if (p == "bigguy-closeup")
        results.push_back(measurePath(context,
                                      guy->name + ", close-up orbit (14 degree field of view)",
                                      *guy, orbitPath(*guy, o, 14.0), o));
      else
        throw Error("--paths: unknown path '" + p + "'");
      if (want('F')) printPath(results.back(), o, csv.get());
    }
    if (want('B')) printBreakEven(results, o);
    progress("done");
    return 0;
  });
}
