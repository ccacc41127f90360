#include "adapters/load_mesh.h"

#include "osd_cull/error.h"

#include <algorithm>
#include <cctype>

namespace osd_cull::adapters {

namespace {
std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}
}  // namespace

bool isBezierPatchFile(const std::filesystem::path& path) { return lowerExtension(path) == ".bpt"; }

}  // namespace osd_cull::adapters
