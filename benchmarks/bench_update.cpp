// bench-update: per-frame update of all patch control points from a moving cage, on the
// GPU (GpuPointUpdate: cage upload + stencil kernel, one submission) and on the CPU
// (PatchPointMatrix::update, float, one thread), BigGuy at isolation levels 1-3.
//
// Time is wall clock around submit-and-wait (PLATFORM.md: compute timestamps are not
// trustworthy after graphics work on lavapipe). GPU and CPU frames alternate in one run,
// so both see the same machine load; figures are medians, the ratio is GPU / CPU.
//
// Usage: bench-update [MESH.obj] [--frames N] [--levels 1,2,3]
#include "adapters/load_mesh.h"
#include "bench_support.h"
#include "osd_cull/error.h"
#include "osd_cull/osd/gpu_point_update.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/vk/context.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

using osd_cull::bench::median;

std::filesystem::path defaultMesh() {
  if (const char* dir = std::getenv("OSD_CULL_DATA_DIR"))
    return std::filesystem::path(dir) / "characters" / "bigguy.obj";
  return std::filesystem::path(OSD_CULL_SOURCE_DIR) / ".." / "shared" / "data" / "characters" /
         "bigguy.obj";
}

// Cage poses: a travelling wave of 2% of the cage size, different each frame.
std::vector<std::vector<float>> makePoses(const osd_cull::CageMesh& cage, int count) {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::dvec3& p : cage.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const double amplitude = 0.02 * glm::length(hi - lo);
  std::vector<std::vector<float>> poses(static_cast<size_t>(count));
  for (int f = 0; f < count; ++f)
    for (const glm::dvec3& p : cage.positions) {
      const double phase = 0.1 * f + 3.0 * (p.y - lo.y) / (hi.y - lo.y + 1e-30);
      const glm::dvec3 q = p + amplitude * glm::dvec3(std::sin(phase), 0.0, std::cos(phase));
      poses[f].insert(poses[f].end(),
                      {static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z)});
    }
  return poses;
}

struct Row {
  int level = 0;
  uint32_t patches = 0;
  uint32_t points = 0;
  size_t nonZeros = 0;
  double gpuSubmitMs = 0, gpuMs = 0, cpuMs = 0;
  double gpuError = 0, cpuError = 0;  // max |float - double| / bounding-box diagonal
};

Row measure(osd_cull::vulkan::Context& context, const osd_cull::CageMesh& cage, int level, int frames) {
  osd_cull::PatchOptions options;
  options.isolationLevel = level;
  const osd_cull::PatchExtraction ex = osd_cull::extractPatches(cage, options);
  const osd_cull::PatchPointMatrix& matrix = ex.matrix;

  osd_cull::osd::DeviceContext device(context);
  osd_cull::osd::GpuPointUpdate gpu(device, matrix);
  const std::vector<std::vector<float>> poses = makePoses(cage, 16);
  std::vector<float> cpuPoints(3 * static_cast<size_t>(matrix.rowCount()));

  // Warm-up: pipeline JIT, first-touch of buffers and caches.
  for (int i = 0; i < 3; ++i) {
    gpu.update(poses[i % poses.size()]);
    gpu.wait();
    matrix.update(poses[i % poses.size()], cpuPoints);
  }
  std::vector<double> submitMs, gpuMs, cpuMs;
  for (int f = 0; f < frames; ++f) {
    const std::vector<float>& pose = poses[f % poses.size()];
    auto start = Clock::now();
    gpu.update(pose);
    submitMs.push_back(msSince(start));
    gpu.wait();
    gpuMs.push_back(msSince(start));
    start = Clock::now();
    matrix.update(pose, cpuPoints);
    cpuMs.push_back(msSince(start));
  }

  // Accuracy of the last frame: both float paths against the double product of the same
  // matrix and the same (float) cage positions, relative to the points' bounding box.
  const std::vector<float>& lastPose = poses[(frames - 1) % poses.size()];
  std::vector<glm::dvec3> cageD(lastPose.size() / 3), exact(cpuPoints.size() / 3);
  for (size_t v = 0; v < cageD.size(); ++v)
    cageD[v] = glm::dvec3(lastPose[3 * v], lastPose[3 * v + 1], lastPose[3 * v + 2]);
  matrix.update(cageD, exact);
  const std::vector<float> gpuPoints = gpu.readback();
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  double gpuWorst = 0.0, cpuWorst = 0.0;
  for (size_t p = 0; p < exact.size(); ++p) {
    lo = glm::min(lo, exact[p]);
    hi = glm::max(hi, exact[p]);
    for (int k = 0; k < 3; ++k) {
      gpuWorst = std::max(gpuWorst, std::abs(gpuPoints[3 * p + k] - exact[p][k]));
      cpuWorst = std::max(cpuWorst, std::abs(cpuPoints[3 * p + k] - exact[p][k]));
    }
  }
  Row row;
  row.level = level;
  row.patches = ex.patches.patchCount();
  row.points = static_cast<uint32_t>(matrix.rowCount());
  row.nonZeros = matrix.nonZeroCount();
  row.gpuSubmitMs = median(submitMs);
  row.gpuMs = median(gpuMs);
  row.cpuMs = median(cpuMs);
  row.gpuError = gpuWorst / glm::length(hi - lo);
  row.cpuError = cpuWorst / glm::length(hi - lo);
  return row;
}

// The fixed cost of one GPU update: the same cage upload, submission and fence wait with a
// one-row matrix (one control point, one weight).
double measureOverheadMs(osd_cull::vulkan::Context& context, const osd_cull::CageMesh& cage,
                         int frames) {
  const osd_cull::PatchPointMatrix one(cage.vertexCount(), {1}, {0}, {1.0});
  osd_cull::osd::DeviceContext device(context);
  osd_cull::osd::GpuPointUpdate gpu(device, one);
  const std::vector<std::vector<float>> poses = makePoses(cage, 16);
  std::vector<double> ms;
  for (int f = -3; f < frames; ++f) {
    const auto start = Clock::now();
    gpu.update(poses[static_cast<size_t>(f + 3) % poses.size()]);
    gpu.wait();
    if (f >= 0) ms.push_back(msSince(start));
  }
  return median(ms);
}

std::vector<int> parseLevels(const std::string& text) {
  std::vector<int> levels;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = text.find(',', start);
    levels.push_back(std::stoi(text.substr(start, comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return levels;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::filesystem::path mesh = defaultMesh();
    int frames = 50;
    std::vector<int> levels = {1, 2, 3};
    std::string meshFile = mesh.string(), levelList = "1,2,3";
    if (!osd_cull::bench::CommandLine("bench-update", "bench_update.cpp")
             .positional("mesh", meshFile)
             .integer("--frames", frames, 1)
             .text("--levels", levelList)
             .parse(argc, argv))
      return 0;
    mesh = meshFile;
    levels = parseLevels(levelList);
    if (!std::filesystem::exists(mesh)) {
      std::fprintf(stderr, "bench-update: %s not found (set OSD_CULL_DATA_DIR or pass a mesh)\n",
                   mesh.string().c_str());
      return 2;
    }
    const osd_cull::CageMesh cage = osd_cull::adapters::loadCage(mesh);
    osd_cull::vulkan::Context context;
    std::printf("mesh %s: %d cage vertices; device %s (%s); %d frames per level\n",
                mesh.filename().string().c_str(), cage.vertexCount(), context.info().name.c_str(),
                context.info().driver.c_str(), frames);
    if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
      char line[128] = {};
      if (std::fgets(line, sizeof(line), f)) std::printf("load average at start: %s", line);
      std::fclose(f);
    }
    std::printf(
        "fixed cost of a GPU update (cage upload + submit + wait, 1-point matrix): "
        "%.3f ms\n",
        measureOverheadMs(context, cage, frames));
    std::printf(
        "| level | patches | control points | non-zeros | GPU submit ms | GPU update ms "
        "| CPU update ms | GPU / CPU | GPU error | CPU error |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
    for (int level : levels) {
      const Row r = measure(context, cage, level, frames);
      std::printf("| %d | %u | %u | %zu | %.3f | %.3f | %.3f | %.2f | %.1e | %.1e |\n", r.level,
                  r.patches, r.points, r.nonZeros, r.gpuSubmitMs, r.gpuMs, r.cpuMs,
                  r.gpuMs / r.cpuMs, r.gpuError, r.cpuError);
      std::fflush(stdout);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench-update: %s\n", e.what());
    return 1;
  }
}
