// bench-scale: how set-up, memory, culling and drawing grow with the patch count, on the
// closed quad-grid torus of osd_cull/scene/procedural.h (one Bezier patch per cage face).
// Prints a Markdown table; see docs/results/scale.md.
//
//   bench-scale [--grids 100,316,700,1000] [--level 1] [--method tcone] [--views 3]
//               [--repeats 3] [--tess 4] [--width 256] [--height 256] [--matrix]
//               [--setup-only] [--cones] [--device X]
//
// Each grid size runs in its own child process (one after the other), so that its peak RSS
// (VmHWM of /proc/self/status) is its own. Per size:
// - set-up (alone with --setup-only, which prints only these columns and the peak RSS in
//   MB): the stages of extractPatches
// (topology, refinement, patch table, stencils, and
//   the points — with --matrix the cage -> point matrix too), the GpuPatchSet upload and the
//   CullPass construction (kernel, cones), wall clock, and the CPU time of extractPatches;
// - memory: peak RSS, per patch, and per patch above the RSS before extraction (Vulkan
//   instance, device and driver; on lavapipe device memory is process memory and counts),
//   and what each stage added to the RSS (extraction, GpuPatchSet upload, CullPass, the
//   cull and draw runs);
// - cull: one pass (frustum + --method) per submission, wall clock median over views x
//   repeats, per patch;
// - draw: all patches at uniform tessellation --tess, median wall ms over the views, and the
//   tessellation-evaluation invocations of the first view (exact).
// --cones instead times the host cones of --method (bound::buildPatchCones, what CullPass
// construction spends its time on): the exhaustive axis search on one thread, the filtered
// search on one thread and on the hardware's threads, interleaved, --repeats rounds,
// median wall and CPU ms each, and checks that all three give bit-identical cones.
#include "bench_support.h"
#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/procedural.h"
#include "osd_cull/vk/context.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace {

using namespace osd_cull;
using osd_cull::bench::median;
using Clock = std::chrono::steady_clock;

struct Options {
  std::vector<uint32_t> grids = {100, 316, 700, 1000};
  int level = 1;
  std::string method = "tcone";
  uint32_t views = 3, repeats = 3, tess = 4, width = 256, height = 256;
  bool matrix = false;
  bool setupOnly = false;
  bool cones = false;
  std::string device;
};

// The options (the comment at the top); false after --help.
bool parse(int argc, char** argv, Options& o) {
  int level = o.level;
  const bool run = bench::CommandLine("bench-scale", "bench_scale.cpp")
                       .numbers("--grids", o.grids)
                       .integer("--level", level, 0)
                       .text("--method", o.method)
                       .number("--views", o.views, 1)
                       .number("--tess", o.tess, 1)
                       .imageAndDevice(o.width, o.height, o.repeats, o.device)
                       .flag("--matrix", o.matrix)
                       .flag("--setup-only", o.setupOnly)
                       .flag("--cones", o.cones)
                       .parse(argc, argv);
  o.level = level;
  return run;
}

// A field of /proc/self/status in bytes (VmRSS: now, VmHWM: peak).
double statusBytes(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(field, 0) == 0)
      return 1024.0 * std::stod(line.substr(std::string(field).size()));
  return 0.0;
}

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

bool sameCones(const std::vector<bound::ConeOfNormals>& a,
               const std::vector<bound::ConeOfNormals>& b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](const auto& x, const auto& y) {
           return std::memcmp(&x, &y, offsetof(bound::ConeOfNormals, valid)) == 0 &&
                  x.valid == y.valid && x.reason == y.reason;
         });
}

// --cones: the three ways of building the host cones, interleaved (see the file comment).
void timeCones(const Options& o, const PatchSet& set) {
  const bound::BackPatchMethod method =
      o.method == "ncone" ? bound::BackPatchMethod::NCone : bound::BackPatchMethod::TCone;
  struct Variant {
    const char* name;
    bound::ConeSearch search;
    unsigned threads;
    std::vector<double> wall, cpu;
    std::vector<bound::ConeOfNormals> cones;
  };
  Variant variants[] = {{"exhaustive, 1 thread", bound::ConeSearch::Exhaustive, 1, {}, {}, {}},
                        {"filtered, 1 thread", bound::ConeSearch::Filtered, 1, {}, {}, {}},
                        {"filtered, all threads", bound::ConeSearch::Filtered, 0, {}, {}, {}}};
  for (uint32_t r = 0; r < o.repeats; ++r)
    for (Variant& v : variants) {
      const std::clock_t cpuStart = std::clock();
      const auto start = Clock::now();
      v.cones = bound::buildPatchCones(set, method, v.search, v.threads);
      v.wall.push_back(msSince(start));
      v.cpu.push_back(1000.0 * double(std::clock() - cpuStart) / CLOCKS_PER_SEC);
    }
  const bool same = sameCones(variants[0].cones, variants[1].cones) &&
                    sameCones(variants[0].cones, variants[2].cones);
  const double base = median(variants[0].wall);
  for (const Variant& v : variants)
    std::printf("| %u | %s | %s | %.0f | %.0f | %.2f | %s |\n", set.patchCount(), o.method.c_str(),
                v.name, median(v.wall), median(v.cpu), base / median(v.wall), same ? "yes" : "NO");
  std::fflush(stdout);
  if (!same) throw Error("the cone searches disagree");
}

void runGrid(const Options& o, uint32_t grid) {
  vulkan::ContextOptions co;
  co.device = o.device;
  vulkan::Context context(co);
  const double baseline = statusBytes("VmRSS:");

  PatchOptions po;
  po.isolationLevel = o.level;
  po.pointMatrix = o.matrix;
  std::optional<CageMesh> cage = scene::torus(int(grid), int(grid), 1.0, 0.4);
  const std::clock_t cpuStart = std::clock();
  const PatchExtraction ex = extractPatches(*cage, po);
  cage.reset();  // a static mesh needs its cage no more
  // CPU time of the set-up (all threads): less disturbed than wall time on a shared machine.
  const double setupCpuMs = 1000.0 * double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  const PatchSet& set = ex.patches;
  const uint32_t n = set.patchCount();
  if (o.setupOnly) {
    const ExtractionStats& st = ex.stats;
    std::printf("| %u | %u | %.0f | %.0f | %.0f | %.0f | %.0f | **%.0f** | %.0f | %.0f |\n", grid,
                n, st.topologyMs, st.refineMs, st.patchTableMs, st.stencilMs, st.matrixMs,
                st.totalMs, setupCpuMs, statusBytes("VmHWM:") / 1048576.0);
    std::fflush(stdout);
    return;
  }
  if (o.cones) {
    timeCones(o, set);
    return;
  }
  std::vector<double> rss = {statusBytes("VmRSS:")};  // after each stage

  auto start = Clock::now();
  frame::GpuPatchSet gpu(context, set);
  const double uploadMs = msSince(start);
  rss.push_back(statusBytes("VmRSS:"));
  frame::CullSettings settings;
  settings.backPatch = o.method;
  settings.backPatchValidity = {true, "closed torus"};
  start = Clock::now();
  frame::CullPass pass(context, gpu, set, settings);
  const double passMs = msSince(start);
  rss.push_back(statusBytes("VmRSS:"));

  frame::ViewSetOptions vo;
  vo.count = o.views;
  vo.width = o.width;
  vo.height = o.height;
  const auto cameras = frame::randomViews(frame::boundsOf(set.points), vo);
  pass.run(cameras[0]);  // warm-up
  std::vector<double> cullMs;
  for (const auto& camera : cameras)
    for (uint32_t r = 0; r < o.repeats; ++r) cullMs.push_back(pass.run(camera));

  frame::Renderer renderer(context);
  frame::RenderTarget target(context, o.width, o.height);
  frame::RenderOptions ro;
  ro.tessellation.uniformLevel = o.tess;
  std::vector<double> drawMs;
  uint64_t tes = 0;
  renderer.render(target, cameras[0], gpu, nullptr, ro);  // warm-up
  for (const auto& camera : cameras) {
    const frame::FrameStats s = renderer.render(target, camera, gpu, nullptr, ro);
    drawMs.push_back(s.wallMs);
    if (tes == 0) tes = s.statistics.tessEvaluationInvocations;
  }

  rss.push_back(statusBytes("VmRSS:"));
  const ExtractionStats& st = ex.stats;
  const double setupMs = st.totalMs;  // topology included
  const double peak = statusBytes("VmHWM:");
  std::printf(
      "| %u | %u | %.0f | %.0f | %.0f | %.0f | %.0f | **%.0f** | %.0f | %.0f | %.0f | %.0f | "
      "**%.0f** | "
      "%.0f | **%.0f** | %.0f | %llu | %.0f / %.0f / %.0f / %.0f |\n",
      grid, n, st.topologyMs, st.refineMs, st.patchTableMs, st.stencilMs, st.matrixMs, setupMs,
      setupCpuMs, uploadMs, passMs, peak / 1048576.0, peak / n, (peak - baseline) / n,
      median(cullMs) * 1e6 / n, median(drawMs), static_cast<unsigned long long>(tes),
      (rss[0] - baseline) / n, (rss[1] - rss[0]) / n, (rss[2] - rss[1]) / n, (rss[3] - rss[2]) / n);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    Options o;
    if (!parse(argc, argv, o)) return 0;
    std::printf(
        "bench-scale: torus grids at isolation level %d, frustum + %s, %u views x %u repeats, "
        "draw at uniform tess %u in %ux%u, matrix %s\n\n",
        o.level, o.method.c_str(), o.views, o.repeats, o.tess, o.width, o.height,
        o.matrix ? "built" : "not built");
    if (o.cones) {
      std::printf("host cones (bound::buildPatchCones), %u interleaved rounds, medians\n\n",
                  o.repeats);
      std::printf(
          "| patches | method | search | wall ms | CPU ms | speed-up (wall) | bit-identical "
          "|\n|---|---|---|---|---|---|---|\n");
    } else {
      std::printf(
          "| grid | patches | topology ms | refine ms | patch table ms | stencils ms | points ms | "
          "set-up ms | set-up CPU ms | upload ms | cull pass ms | peak RSS MB | bytes/patch | "
          "above "
          "baseline "
          "B/patch | cull ns/patch | draw ms | TES invocations | RSS B/patch added by extraction / "
          "upload / cull pass / runs |\n");
      std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    }
    std::fflush(stdout);
    int failures = 0;
    for (uint32_t grid : o.grids) {
      const pid_t child = fork();
      if (child < 0) throw Error("bench-scale: fork failed");
      if (child == 0) {
        try {
          runGrid(o, grid);
        } catch (const std::exception& e) {
          std::fprintf(stderr, "bench-scale: grid %u: %s\n", grid, e.what());
          std::fflush(stderr);
          _exit(1);
        }
        _exit(0);
      }
      int status = 0;
      waitpid(child, &status, 0);
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) ++failures;
    }
    return failures == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench-scale: %s\n", e.what());
    return 1;
  }
}
