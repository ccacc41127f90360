#pragma once
/// \file cull_methods.h
/// \brief The registry of cull methods the cull kernel can run (frustum, tcone, ncone,
/// tangent-plane, tangent-plane-16, tcone-fp64, ncone-fp64, hiz and the displaced kernels).
///
/// A method is one GLSL file under shaders/cull/ defining its stage function (see
/// shaders/cull/cull_main.glsl for the signatures) and one C++ function returning its
/// CullMethod, listed in cullMethods() (cull_methods.cpp). So a new method is a new GLSL
/// file, a new .cpp with its description, and one line in the registry. (Self-registering
/// static objects would be dropped by the linker from the static library.)

#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/bound/displaced_bounds.h"
#include "osd_cull/vk/descriptors.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace osd_cull::frame {

/// \brief Where a method runs in the kernel; stages run in this order, cheapest first, and
/// a patch culled by one stage skips the later ones.
enum class CullStage : uint32_t { Frustum = 1, BackPatch = 2, Occlusion = 3 };

/// \brief "frustum", "back-patch", "occlusion".
const char* toString(CullStage stage);

/// \brief One cull method: what the kernel includes and what the host prepares for it.
struct CullMethod {
  std::string name;  ///< command-line name, e.g. "tangent-plane-16"
  CullStage stage = CullStage::BackPatch;
  std::string summary;   ///< one line for help texts and reports
  std::string glslFile;  ///< embedded file (relative to shaders/) with the stage function
  /// Threads per patch of the kernel variant (1, or 16 for the section 6 scheme).
  uint32_t lanesPerPatch = 1;
  /// The kernel computes in double: the device needs shaderFloat64 (CullPass says so).
  bool needsFloat64 = false;
  /// GLSL declarations placed before the stage file (e.g. the size of a generated table);
  /// empty when none.
  std::function<std::string()> generatedGlsl;
  /// A constant table the stage reads from the table buffer (shaders/shared/cull_layout.h
  /// kCullBindingTable, two words per entry); empty when none.
  std::function<std::vector<uint32_t>()> table;
  /// Back-patch stage: the CPU reference it mirrors, which also selects the cones
  /// (bound::buildPatchCones) the host uploads for it.
  bound::BackPatchMethod reference = bound::BackPatchMethod::None;
  /// Occlusion stage: the bindings of its descriptor set (set 1), passed to CullPass::record.
  std::vector<vulkan::DescriptorBinding> stageBindings;
  /// Displaced kernels (cull_method_displaced.cpp): Hi-Z occlusion, and the frustum test of
  /// the same pass, on this displaced bound of a displaced mesh (CullSettings::displacement).
  struct Displaced {
    bound::DisplacedExtension extension = bound::DisplacedExtension::ACoN;
    bound::DisplacedBox box = bound::DisplacedBox::CAF;
  };
  std::optional<Displaced> displaced;
};

/// \brief Every registered method, in stage order.
std::span<const CullMethod> cullMethods();

/// \brief The method called `name`.
/// \throws osd_cull::Error listing the registered names when there is none.
const CullMethod& cullMethod(std::string_view name);

/// \brief Names of the registered methods of one stage, in registry order.
std::vector<std::string> cullMethodNames(CullStage stage);

// The registrations (one per file: cull_method_*.cpp).
CullMethod frustumCullMethod();
CullMethod tconeCullMethod();
CullMethod nconeCullMethod();
CullMethod tconeFp64CullMethod();
CullMethod nconeFp64CullMethod();
CullMethod tangentPlaneCullMethod();
CullMethod tangentPlane16CullMethod();
CullMethod hizCullMethod();
/// \brief The six displaced kernels full-oobb ... con-caf (Niessner & Loop Table 1).
std::vector<CullMethod> displacedCullMethods();

}  // namespace osd_cull::frame
