// The same-image benchmark of issue 10 (docs/results/animation.md, section "Same image over
// 300 frames"): the built-in scene (a skinned character swinging its limbs among static and
// moving objects, the camera on its path, a sun view) played frame after frame with culling
// (frustum, the back-patch method, Hi-Z occlusion: Niessner & Loop §3's two-pass frame),
// and every frame of every view drawn again without culling, like for like (same
// tessellation, back-face culling, image size). The item images must agree: no pixel lost
// (covered unculled, background culled), fewer than 0.01% differing (depth ties between
// neighbouring patches).
//
// Usage: bench-scene-image [--frames N] [--size WxH] [--tess L] [--back-patch METHOD]
//                          [--gpu-points] [--every K]
//   prints every K-th frame (default 10) and the frames with a lost pixel or over 0.01%
//   differing, then the worst figures and medians over all frames and views; exits 1 when
//   a pixel was lost or a frame differed by 0.01% or more.
#include "bench_support.h"
#include "osd_cull/error.h"
#include "osd_cull/scene/default_scene.h"
#include "osd_cull/scene/scene_player.h"
#include "osd_cull/vk/context.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

struct Args {
  uint32_t frames = 300;
  uint32_t width = 160, height = 120;
  uint32_t tess = 4;
  std::string backPatch = "ncone";
  bool gpuPoints = false;
  uint32_t every = 10;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw Error(arg + ": needs a value");
      return argv[++i];
    };
    if (arg == "--frames") {
      a.frames = uint32_t(std::stoul(value()));
    } else if (arg == "--size") {
      const std::string v = value();
      if (std::sscanf(v.c_str(), "%ux%u", &a.width, &a.height) != 2 || !a.width || !a.height)
        throw Error("--size: expected WxH, got '" + v + "'");
    } else if (arg == "--tess") {
      a.tess = uint32_t(std::stoul(value()));
    } else if (arg == "--back-patch") {
      a.backPatch = value();
    } else if (arg == "--gpu-points") {
      a.gpuPoints = true;
    } else if (arg == "--every") {
      a.every = std::max(1u, uint32_t(std::stoul(value())));
    } else {
      throw Error("unknown argument '" + arg + "' (see the comment at the top of the file)");
    }
  }
  if (a.frames == 0) throw Error("--frames: at least 1");
  return a;
}

int run(const Args& a) {
  scene::LoadedScene s = scene::builtInScene(a.frames);
  s.description.settings.width = a.width;
  s.description.settings.height = a.height;
  scene::ViewDescription sun;
  sun.name = "sun";
  sun.kind = scene::ViewDescription::Kind::Shadow;
  sun.lightDirection = {-0.4, 0.5, -1.0};
  sun.width = sun.height = a.height;
  s.description.views.push_back(sun);

  vulkan::Context context;
  frame::CullFrameOptions options;
  options.render.tessellation.uniformLevel = a.tess;
  options.render.cullBackFaces = true;
  options.cull.backPatch = a.backPatch;
  scene::ScenePlayer player(
      context, s, options, a.gpuPoints ? frame::PointUpdatePath::Gpu : frame::PointUpdatePath::Cpu);
  std::printf(
      "scene: %s, %zu instances, %u patches, %zu views, %u frames, tess %u, %s, %s "
      "point update, device %s\n",
      s.description.source.c_str(), player.instanceCount(), player.patchCount(), player.viewCount(),
      a.frames, a.tess, a.backPatch.c_str(), a.gpuPoints ? "GPU" : "CPU",
      context.info().name.c_str());
  for (const std::string& line : player.describe()) std::printf("  %s\n", line.c_str());

  std::vector<std::unique_ptr<frame::RenderTarget>> plain;
  for (size_t v = 0; v < player.viewCount(); ++v)
    plain.push_back(std::make_unique<frame::RenderTarget>(context, player.target(v).width(),
                                                          player.target(v).height()));
  struct Worst {
    uint64_t lost = 0;
    double differing = 0.0;  // share of the image
    uint32_t frame = 0;
  };
  std::vector<Worst> worst(player.viewCount());
  std::vector<std::vector<double>> culledShare(player.viewCount()), tesRatio(player.viewCount()),
      culledMs(player.viewCount()), plainMs(player.viewCount());
  uint32_t failedFrames = 0;
  std::printf("\n%6s %-5s %9s %8s %6s %11s %10s %9s %9s\n", "frame", "view", "culled", "covered",
              "lost", "differing", "TES ratio", "culled ms", "plain ms");
  for (uint32_t f = 0; f < a.frames; ++f) {
    const std::vector<scene::ViewFrame> views = player.render(f);
    bool failed = false;
    for (size_t v = 0; v < views.size(); ++v) {
      // Each culled frame is followed by its unculled draw: the two are interleaved.
      const scene::UnculledComparison c = player.compareWithUnculled(v, *plain[v]);
      const frame::CullFrameStats& st = views[v].stats;
      const double differing = double(c.differing) / double(c.pixels);
      const uint64_t culledTes =
                         st.pass1.tessEvaluationInvocations + st.pass2.tessEvaluationInvocations,
                     plainTes = c.unculled.statistics.tessEvaluationInvocations;
      const double ratio = plainTes ? double(culledTes) / double(plainTes) : 1.0;
      culledShare[v].push_back(double(st.culled()) / double(st.patchesTotal));
      tesRatio[v].push_back(ratio);
      culledMs[v].push_back(st.totalMs());
      plainMs[v].push_back(c.unculled.wallMs);
      if (c.lost > worst[v].lost || differing > worst[v].differing)
        worst[v] = {std::max(worst[v].lost, c.lost), std::max(worst[v].differing, differing), f};
      const bool bad = c.lost > 0 || differing >= 1e-4;
      failed |= bad;
      if (bad || f % a.every == 0 || f + 1 == a.frames)
        std::printf("%6u %-5s %8.1f%% %8llu %6llu %10.4f%% %10.3f %9.2f %9.2f%s\n", f,
                    views[v].view.c_str(), 100.0 * culledShare[v].back(),
                    static_cast<unsigned long long>(c.covered),
                    static_cast<unsigned long long>(c.lost), 100.0 * differing, ratio, st.totalMs(),
                    c.unculled.wallMs, bad ? "  <-- FAILS" : "");
    }
    failedFrames += failed;
  }

  std::printf("\nsummary over %u frames (worst: largest over all frames; medians per frame)\n",
              a.frames);
  std::printf("%-5s %10s %15s %11s %14s %15s %12s\n", "view", "worst lost", "worst differing",
              "at frame", "median culled", "median TES/plain", "median ms c/p");
  for (size_t v = 0; v < player.viewCount(); ++v)
    std::printf("%-5s %10llu %14.4f%% %11u %13.1f%% %15.3f %6.2f/%.2f\n",
                s.description.views[v].name.c_str(), static_cast<unsigned long long>(worst[v].lost),
                100.0 * worst[v].differing, worst[v].frame, 100.0 * bench::median(culledShare[v]),
                bench::median(tesRatio[v]), bench::median(culledMs[v]), bench::median(plainMs[v]));
  for (const scene::MeshWork& w : player.work())
    std::printf("mesh '%s': %s, %llu point updates, %llu bounds dispatches\n", w.mesh.c_str(),
                w.deforms ? "deforms" : "static", static_cast<unsigned long long>(w.pointUpdates),
                static_cast<unsigned long long>(w.boundsDispatches));
  std::printf("frames failing (a pixel lost or >= 0.01%% differing): %u of %u\n", failedFrames,
              a.frames);
  if (const vulkan::ValidationLog* log = context.validationLog(); log && log->count() > 0) {
    std::fprintf(stderr, "validation reported %llu messages\n",
                 static_cast<unsigned long long>(log->count()));
    return 1;
  }
  return failedFrames == 0 ? 0 : 1;
}

}  // namespace
}  // namespace osd_cull

int main(int argc, char** argv) {
  try {
    return osd_cull::run(osd_cull::parse(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench-scene-image: %s\n", e.what());
    return 2;
  }
}
