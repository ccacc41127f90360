#include "osd_cull/frame/shader_variants.h"

#include <set>

namespace osd_cull::frame {

std::vector<vulkan::ShaderVariant> libraryShaderVariants() {
  std::vector<vulkan::ShaderVariant> all;
  std::set<std::string> keys;
  for (auto* list : {rendererShaderVariants, cullPassShaderVariants, boundsPassShaderVariants,
                     hizPyramidShaderVariants, visibilityShaderVariants, oracleShaderVariants,
                     osd::evaluatorShaderVariants})
    for (vulkan::ShaderVariant& v : list())
      if (keys.insert(v.key()).second) all.push_back(std::move(v));
  return all;
}

}  // namespace osd_cull::frame
