// Registration of the Hi-Z occlusion stage (shaders/cull/occlusion_hiz.glsl); its
// descriptor set is made by HiZCullStage (hiz_cull_stage.h).
#include "osd_cull/frame/cull/cull_methods.h"
#include "osd_cull/frame/hiz/hiz_cull_stage.h"

namespace osd_cull::frame {

CullMethod hizCullMethod() {
  CullMethod m;
  m.name = "hiz";
  m.stage = CullStage::Occlusion;
  m.summary =
      "Hi-Z occlusion: the patch's screen box against the depth pyramid of the frame's "
      "first pass (Niessner & Loop)";
  m.glslFile = "cull/occlusion_hiz.glsl";
  const auto bindings = hizStageBindings();
  m.stageBindings.assign(bindings.begin(), bindings.end());
  return m;
}

}  // namespace osd_cull::frame
