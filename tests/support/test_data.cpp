#include "support/test_data.h"

#include <algorithm>
#include <cstdlib>

namespace osd_cull::test {

std::filesystem::path dataDir() {
  if (const char* env = std::getenv("OSD_CULL_DATA_DIR"); env && *env) return env;
  return std::filesystem::path(OSD_CULL_SOURCE_DIR) / ".." / "shared" / "data";
}

bool haveData() { return std::filesystem::is_directory(dataDir() / "shapes"); }

std::vector<std::filesystem::path> catmarkShapes() {
  std::vector<std::filesystem::path> out;
  if (!haveData()) return out;
  for (const auto& entry : std::filesystem::directory_iterator(dataDir() / "shapes")) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with("catmark_") && entry.path().extension() == ".obj") out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace osd_cull::test
