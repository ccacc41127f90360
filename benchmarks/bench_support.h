#pragma once
/// \file bench_support.h
/// \brief Small helpers shared by the benchmarks.

#include "adapters/load_mesh.h"
#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace osd_cull::bench {

/// \brief The median (mean of the two middle values for an even count); 0 when empty.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

/// \brief The body of a benchmark's main(): runs `body` and returns its exit code; an
/// exception is printed as "NAME: what" and gives exit code 2.
template <class Body>
int guardedMain(const char* name, Body&& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return 2;
  }
}

/// \brief A comma-separated list of unsigned numbers ("4,8,16").
/// \throws std::invalid_argument or std::out_of_range for an item that is not a number.
inline std::vector<uint32_t> numberList(const std::string& text) {
  std::vector<uint32_t> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(static_cast<uint32_t>(std::stoul(item)));
  return out;
}

/// \brief The data folder beside the project (as the tests find it), or $OSD_CULL_DATA_DIR.
inline std::filesystem::path dataDir() {
  if (const char* d = std::getenv("OSD_CULL_DATA_DIR")) return d;
  return std::filesystem::path(OSD_CULL_SOURCE_DIR) / ".." / "shared" / "data";
}

/// \brief Patches of a cage file at an isolation level, and whether back-patch culling (and
/// so rasterizer back-face culling) is valid on it: a closed, consistently oriented mesh.
struct CullMesh {
  PatchSet patches;
  bound::BackPatchValidity validity;
};

/// \brief Loads `path` and extracts its patches at isolation `level`.
inline CullMesh loadCullMesh(const std::filesystem::path& path, uint32_t level) {
  const CageMesh cage = adapters::loadCage(path);
  PatchOptions options;
  options.isolationLevel = static_cast<int>(level);
  return {
      extractPatches(cage, options).patches,
      bound::backPatchValidity(summarize(*makeTopologyRefiner(cage)), bound::signedVolume(cage))};
}

}  // namespace osd_cull::bench
