// Registrations of the displaced kernels (shaders/cull/displaced_bound.glsl with the Hi-Z
// stage of occlusion_hiz.glsl): Full, ACoN and CoN extensions of an OOBB or a
// camera-aligned frustum (Niessner & Loop §4.2, Table 1). They run on displaced meshes only
// (CullSettings::displacement); the per-patch Dmin/Dmax and cones are built on the host for
// a static mesh, by the per-frame bounds pass for a deforming one (DynamicPatchMesh).
#include "osd_cull/frame/cull/cull_methods.h"
#include "osd_cull/frame/hiz/hiz_cull_stage.h"

namespace osd_cull::frame {

std::vector<CullMethod> displacedCullMethods() {
  using bound::DisplacedBox;
  using bound::DisplacedExtension;
  const char* extensionText[] = {"uniform extension by max |D| (Sathe)",
                                 "approximate cone of normals (tangent cones)",
                                 "true cone of normals (normal patch)"};
  std::vector<CullMethod> out;
  for (DisplacedBox box : {DisplacedBox::OOBB, DisplacedBox::CAF})
    for (DisplacedExtension e :
         {DisplacedExtension::Full, DisplacedExtension::ACoN, DisplacedExtension::CoN}) {
      CullMethod m;
      m.name = bound::displacedKernelName(e, box);
      m.stage = CullStage::Occlusion;
      m.summary = std::string("displaced Hi-Z occlusion: ") +
                  (box == DisplacedBox::OOBB ? "object-space box" : "camera-aligned frustum") +
                  ", " + extensionText[static_cast<int>(e)] + " (Niessner & Loop 4.2)";
      m.glslFile = "cull/occlusion_hiz.glsl";
      const auto bindings = hizStageBindings();
      m.stageBindings.assign(bindings.begin(), bindings.end());
      m.displaced = CullMethod::Displaced{e, box};
      out.push_back(std::move(m));
    }
  return out;
}

}  // namespace osd_cull::frame
