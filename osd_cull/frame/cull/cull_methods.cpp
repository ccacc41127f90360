#include "osd_cull/frame/cull/cull_methods.h"

#include "osd_cull/error.h"

namespace osd_cull::frame {

const char* toString(CullStage stage) {
  switch (stage) {
    case CullStage::Frustum:
      return "frustum";
    case CullStage::BackPatch:
      return "back-patch";
    case CullStage::Occlusion:
      return "occlusion";
  }
  return "?";
}

std::span<const CullMethod> cullMethods() {
  static const std::vector<CullMethod> methods = [] {
    std::vector<CullMethod> m = {
        frustumCullMethod(),        tconeCullMethod(),
        nconeCullMethod(),          tangentPlaneCullMethod(),
        tangentPlane16CullMethod(), tconeFp64CullMethod(),
        nconeFp64CullMethod(),      hizCullMethod(),
    };
    for (CullMethod& d : displacedCullMethods()) m.push_back(std::move(d));
    return m;
  }();
  return methods;
}

const CullMethod& cullMethod(std::string_view name) {
  std::string known;
  for (const CullMethod& m : cullMethods()) {
    if (m.name == name) return m;
    known += (known.empty() ? "" : ", ") + m.name;
  }
  throw Error("unknown cull method '" + std::string(name) + "' (known: " + known + ")");
}

std::vector<std::string> cullMethodNames(CullStage stage) {
  std::vector<std::string> names;
  for (const CullMethod& m : cullMethods())
    if (m.stage == stage) names.push_back(m.name);
  return names;
}

}  // namespace osd_cull::frame
