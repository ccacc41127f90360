// bench-frame-cost: what culling costs and saves in a whole frame, like for like, for
// docs/results/frame-cost.md. Prints Markdown tables:
//  P. the Hi-Z pyramid build at the image size: the single-pass build against the per-level
//     builds (four-tap and min/max sampler), each in its own submission, interleaved,
//     medians; with an empty submission and the unculled tess-4 frame for scale;
//  F. per camera path and tessellation level, per cull configuration (frustum; frustum +
//     back-patch; frustum + Hi-Z occlusion; all three): x (share of patches not drawn),
//     the ideal ratio 1 - x, the measured time ratio culled / unculled, the share of the
//     ideal saving (1 - ratio) / x, TES and fragment-invocation ratios, and the per-pass
//     split from the same frames in the diagnostic mode;
//  B. the break-even tessellation level per configuration and path.
//
//   bench-frame-cost [--width 1280] [--height 720] [--tess 1,4,8,16,32] [--frames 8]
//                    [--paths default-orbit,default-walk,bigguy-orbit,bigguy-closeup]
//                    [--bigguy-level 2] [--only PFB] [--repeats 20] [--csv FILE]
//                    [--device X]
//
// Both sides of every ratio run the same RenderOptions: the same tessellation, image and
// camera, and back faces culled by the rasterizer where the mesh is closed and oriented.
// The unculled frame is Renderer::render (one submission); the culled frame is
// CullFrame::render (one submission) with occlusion, frame::renderCulled (cull dispatch and
// draws in one submission) without. Frames are interleaved: per camera, the unculled frame,
// then each configuration. Progress goes to stderr.
#include "bench_support.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/vk/context.h"

#include <glm/trigonometric.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace osd_cull;
using osd_cull::bench::median;

struct Options {
  uint32_t width = 1280, height = 720, frames = 8, repeats = 20, bigguyLevel = 2;
  std::vector<uint32_t> tess = {1, 4, 8, 16, 32};
  std::string paths = "default-orbit,default-walk,bigguy-orbit,bigguy-closeup";
  std::string only = "PFB";
  std::string csv, device;
};

using osd_cull::bench::nameList;
using osd_cull::bench::progress;

// False after --help.
bool parse(int argc, char** argv, Options& o) {
  return bench::CommandLine("bench-frame-cost", "bench_frame_cost.cpp")
      .imageAndDevice(o.width, o.height, o.repeats, o.device)
      .number("--frames", o.frames, 1)
      .number("--bigguy-level", o.bigguyLevel)
      .numbers("--tess", o.tess)
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
// outside the bounding sphere.
Path orbitPath(const Scene& s, const Options& o, double fovyDegrees) {
  const frame::Bounds b = frame::boundsOf(s.patches.points);
  const frame::Camera framed =
      frame::frameBounds(b, s.viewDirection, s.up, 40.0, o.width, o.height);
  const double d = glm::distance(framed.eye(), b.center()), r = b.radius();
  const frame::Camera start =
      frame::Camera::lookAt(framed.eye(), b.center(), s.up, fovyDegrees, o.width, o.height,
                            std::max(d - 1.5 * r, d * 1e-3), d + 1.5 * r);
  const double step = 360.0 / o.frames;
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
  bool backPatch = false, occlusion = false;
};
const Config kConfigs[] = {{"frustum", false, false},
                           {"frustum + back-patch", true, false},
                           {"frustum + occlusion", false, true},
                           {"all", true, true}};

frame::CullSettings settings(const Config& c, const Scene& s) {
  return {true, c.backPatch ? "tangent-plane" : "", c.occlusion ? "hiz" : "", s.validity};
}

// Per configuration and tessellation level, over the frames of one path.
struct Row {
  std::vector<double> ratio, pass1, pyramid, cull, pass2, splitTotal;
  uint64_t notDrawn = 0, total = 0, tes = 0, fragments = 0, frustum = 0;
  double plainMs = 0, culledMs = 0;
};

struct PathResult {
  std::string name;
  std::map<std::pair<uint32_t, size_t>, Row> rows;          // (tess, config)
  std::map<uint32_t, std::pair<uint64_t, uint64_t>> plain;  // tess -> TES, fragments
  std::map<uint32_t, double> plainMs;
};

PathResult measurePath(vulkan::Context& context, const std::string& name, const Scene& scene,
                       const Path& path, const Options& o) {
  PathResult result{name, {}, {}, {}};
  frame::GpuPatchSet gpu(context, scene.patches);
  std::vector<frame::GpuTriangleMesh> meshes;
  for (const auto& m : scene.occluders) meshes.emplace_back(context, m);
  std::vector<const frame::GpuTriangleMesh*> occluders;
  for (const auto& m : meshes) occluders.push_back(&m);
  frame::Renderer renderer(context);
  frame::RenderTarget plain(context, o.width, o.height), culled(context, o.width, o.height),
      diagnostic(context, o.width, o.height);
  const frame::CullMesh cullMeshes[] = {{&gpu, &scene.patches}};
  const frame::PatchDraw draw{&gpu, &scene.patches, 0};
  for (uint32_t tess : o.tess) {
    progress("F. " + name + ": tess " + std::to_string(tess));
    frame::RenderOptions render;
    render.tessellation.uniformLevel = tess;
    render.cullBackFaces = scene.validity.enabled;
    std::vector<std::unique_ptr<frame::CullFrame>> frames, splits;
    std::vector<std::unique_ptr<frame::CullPass>> passes;
    for (const Config& c : kConfigs) {
      frame::CullFrameOptions fo;
      fo.render = render;
      fo.cull = settings(c, scene);
      if (c.occlusion) {
        frames.push_back(
            std::make_unique<frame::CullFrame>(context, renderer, culled, cullMeshes, fo));
        fo.timePasses = true;
        splits.push_back(
            std::make_unique<frame::CullFrame>(context, renderer, diagnostic, cullMeshes, fo));
        passes.push_back(nullptr);
      } else {
        frames.push_back(nullptr);
        splits.push_back(nullptr);
        passes.push_back(std::make_unique<frame::CullPass>(context, gpu, scene.patches, fo.cull));
      }
    }
    std::vector<double> plainMs;
    uint64_t plainTes = 0, plainFragments = 0;
    // Frame -1 warms up (pipelines; temporal status at the path's first camera).
    for (int f = -1; f < int(o.frames); ++f) {
      const frame::Camera cam = path(uint32_t(std::max(f, 0)));
      const frame::FrameStats p = renderer.render(plain, cam, {&draw, 1}, occluders, render);
      if (f >= 0) {
        plainMs.push_back(p.wallMs);
        plainTes += p.statistics.tessEvaluationInvocations;
        plainFragments += p.statistics.fragmentShaderInvocations;
      }
      for (size_t c = 0; c < std::size(kConfigs); ++c) {
        Row& row = result.rows[{tess, c}];
        double ms = 0;
        uint32_t drawn = 0, frustum = 0;
        vulkan::PipelineStatistics st;
        if (frames[c]) {
          const frame::CullFrameStats s = frames[c]->render(cam, occluders);
          const frame::CullFrameStats d = splits[c]->render(cam, occluders);
          ms = s.frameMs;
          drawn = s.drawnPass1 + s.drawnPass2;
          frustum = s.culledFrustum;
          st = s.pass1;
          st += s.pass2;
          if (f >= 0) {
            row.pass1.push_back(d.pass1Ms);
            row.pyramid.push_back(d.pyramidMs);
            row.cull.push_back(d.cullMs);
            row.pass2.push_back(d.pass2Ms);
            row.splitTotal.push_back(d.frameMs);
          }
        } else {
          const frame::FrameStats s =
              frame::renderCulled(renderer, culled, cam, *passes[c], occluders, render);
          ms = s.wallMs;
          drawn = s.patchesDrawn;
          st = s.statistics;
          for (uint32_t code : passes[c]->results())
            frustum += bound::CullCode{code}.stage() == shader::kStageFrustum;
          if (f >= 0) {
            row.cull.push_back(passes[c]->run(cam, render.tessellation));
            row.splitTotal.push_back(ms);
          }
        }
        if (f < 0) continue;
        row.ratio.push_back(ms / p.wallMs);
        row.notDrawn += scene.patches.patchCount() - drawn;
        row.total += scene.patches.patchCount();
        row.tes += st.tessEvaluationInvocations;
        row.fragments += st.fragmentShaderInvocations;
        row.frustum += frustum;
      }
    }
    result.plain[tess] = {plainTes, plainFragments};
    result.plainMs[tess] = median(plainMs);
  }
  return result;
}

void printPath(const PathResult& r, const Options& o, FILE* csv) {
  std::printf("\n### %s\n\n", r.name.c_str());
  std::printf(
      "| tess | stages | x (not drawn) | frustum culled | ideal 1-x | ms unculled | ratio | share "
      "of ideal | TES ratio | fragment ratio | split: pass 1 / pyramid / cull / pass 2 ms |\n");
  std::printf("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
  for (uint32_t tess : o.tess)
    for (size_t c = 0; c < std::size(kConfigs); ++c) {
      const Row& row = r.rows.at({tess, c});
      const double x = double(row.notDrawn) / double(row.total);
      const double ratio = median(row.ratio);
      const auto [tes, fragments] = r.plain.at(tess);
      const double share = x > 0 ? (1.0 - ratio) / x : 0.0;
      char split[128];
      if (kConfigs[c].occlusion)
        std::snprintf(split, sizeof split, "%.1f / %.1f / %.1f / %.1f", median(row.pass1),
                      median(row.pyramid), median(row.cull), median(row.pass2));
      else
        std::snprintf(split, sizeof split, "cull %.1f of %.1f", median(row.cull),
                      median(row.splitTotal));
      std::printf(
          "| %u | %s | %.1f%% | %.1f%% | %.2f | %.1f | %.2f | %.0f%% | %.2f | %.2f | %s |\n", tess,
          kConfigs[c].name.c_str(), 100 * x, 100.0 * double(row.frustum) / double(row.total), 1 - x,
          r.plainMs.at(tess), ratio, 100 * share, double(row.tes) / double(tes),
          double(row.fragments) / double(fragments), split);
      if (csv)
        std::fprintf(csv, "\"%s\",\"%s\",%u,%.5f,%.5f,%.5f,%.5f,%.5f,%.3f,%.3f,%.3f,%.3f,%.3f\n",
                     r.name.c_str(), kConfigs[c].name.c_str(), tess, x, ratio,
                     double(row.tes) / double(tes), double(row.fragments) / double(fragments),
                     r.plainMs.at(tess), median(row.pass1), median(row.pyramid), median(row.cull),
                     median(row.pass2), median(row.splitTotal));
    }
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
        if (median(r.rows.at({*t, c}).ratio) >= 1.0) break;
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
    bool legacy;
  };
  std::vector<Kind> kinds = {{"single pass (1 dispatch)", frame::HiZReduction::SinglePass, false},
                             {"per level, four-tap", frame::HiZReduction::FourTap, false},
                             {"per level, four-tap, before (every texel every build)",
                              frame::HiZReduction::FourTap, true}};
  if (frame::supportsMinmaxReduction(context)) {
    kinds.push_back({"per level, min/max sampler, gathered top level (default)",
                     frame::HiZReduction::Sampler, false});
    kinds.push_back({"per level, min/max sampler, before (four-tap top level, every texel)",
                     frame::HiZReduction::Sampler, true});
  }
  std::vector<std::unique_ptr<frame::HiZPyramid>> pyramids;
  std::vector<double> createMs;
  for (const auto& k : kinds) {
    frame::HiZOptions ho;
    ho.reduction = k.reduction;
    ho.legacyBuild = k.legacy;
    createMs.push_back(timed([&] {
      pyramids.push_back(std::make_unique<frame::HiZPyramid>(context, target.depth(), ho));
      pyramids.back()->build(context, frame::RenderTarget::kDepthLayout);
    }));
  }
  std::vector<std::vector<double>> ms(kinds.size());
  for (uint32_t r = 0; r < o.repeats; ++r) {
    frameMs.push_back(renderer.render(target, cam, {&draw, 1}, {}, render).wallMs);
    emptyMs.push_back(timed([&] { context.submit([](VkCommandBuffer) {}); }));
    for (size_t k = 0; k < kinds.size(); ++k)
      ms[k].push_back(
          timed([&] { pyramids[k]->build(context, frame::RenderTarget::kDepthLayout); }));
  }
  const auto& layout = pyramids[0]->layout();
  std::printf(
      "## Hi-Z pyramid build, %ux%u (%u levels from %ux%u), medians over %u interleaved "
      "repeats, each a submission and wait\n\n",
      o.width, o.height, layout.levelCount, layout.levelWidth(0), layout.levelHeight(0), o.repeats);
  std::printf(
      "| build | dispatches | ms | share of the unculled tess-4 frame | first build incl. "
      "pipeline creation, ms |\n|---|---:|---:|---:|---:|\n");
  const double frame = median(frameMs);
  for (size_t k = 0; k < kinds.size(); ++k)
    std::printf("| %s | %u | %.2f | %.1f%% | %.0f |\n", kinds[k].name.c_str(),
                pyramids[k]->dispatchCount(), median(ms[k]), 100 * median(ms[k]) / frame,
                createMs[k]);
  std::printf("| (empty submission) | 0 | %.2f | %.1f%% | |\n", median(emptyMs),
              100 * median(emptyMs) / frame);
  std::printf("\nUnculled built-in scene frame, tess 4, back faces culled: %.2f ms (median)\n",
              frame);
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
                       "path,stages,tess,not_drawn,ratio,tes_ratio,fragment_ratio,unculled_ms,"
                       "pass1_ms,pyramid_ms,cull_ms,pass2_ms,split_total_ms");
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
