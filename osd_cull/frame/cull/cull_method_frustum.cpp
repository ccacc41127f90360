// Registration of the frustum stage (shaders/cull/frustum.glsl).
#include "osd_cull/frame/cull/cull_methods.h"

namespace osd_cull::frame {

CullMethod frustumCullMethod() {
  CullMethod m;
  m.name = "frustum";
  m.stage = CullStage::Frustum;
  m.summary = "view frustum: every control point outside one clip plane (Sathe)";
  m.glslFile = "cull/frustum.glsl";
  return m;
}

}  // namespace osd_cull::frame
