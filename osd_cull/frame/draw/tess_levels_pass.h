#pragma once
/// \file tess_levels_pass.h
/// \brief The levels pass: the adaptive tessellation levels of every patch of a set for one
/// view, computed once in compute (shaders/patch/tess_levels.comp) into
/// GpuPatchSet::tessLevels(), and read by every draw of the set in that view and by the cull
/// kernel's drawn-triangle test (docs/algorithms/drawn-triangles.md, "Exact adaptive
/// levels"). Nießner and Loop compute tessellation factors in the compute pass (§5).

#include "osd_cull/frame/camera.h"
#include "osd_cull/frame/draw/gpu_patch_set.h"
#include "osd_cull/frame/draw/tess_levels.h"
#include "osd_cull/vk/pipeline.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/shader_compiler.h"

#include <osd_cull/shared/draw_layout.h>

#include <vector>

namespace osd_cull::frame {

/// \brief The tessellation fields of DrawConstants (viewProjection, eye, viewport, mode),
/// as every patch draw and the levels pass set them; `effective`: effectiveOptions() of the
/// set.
void writeTessConstants(shader::DrawConstants& c, const Camera& camera,
                        const TessellationOptions& effective);

/// \brief Whether draws of `gpu` with these options read their levels from the levels pass:
/// adaptive tessellation of an undisplaced set (a displaced set's levels add the
/// displacement's variation in the control shader, and it is never back-patch culled).
bool usesTessLevelsPass(const GpuPatchSet& gpu, const TessellationOptions& options);

/// \brief Records the levels pass; one compute pipeline, shared by every set.
class TessLevelsPass {
 public:
  explicit TessLevelsPass(vulkan::Context& context);

  /// \brief Records the levels of every patch of `gpu` for `camera` (composed with `model`
  /// as the draws compose it, frame::instanceCamera; null: identity) into slot `slot` of
  /// gpu.tessLevels(), with barriers: earlier draws and kernels that read the slot finish
  /// first, later control shaders and compute shaders see the new levels.
  /// \throws osd_cull::Error when the slot is not reserved or the options are not adaptive.
  void record(VkCommandBuffer cmd, const Camera& camera, const glm::dmat4* model,
              const GpuPatchSet& gpu, uint32_t slot, const TessellationOptions& options) const;

 private:
  vulkan::UniqueDescriptorSetLayout setLayout_;
  vulkan::UniquePipelineLayout layout_;
  vulkan::UniquePipeline pipeline_;
  uint32_t groupLimit_ = 0;
};

/// \brief Slot `slot` of gpu.tessLevels() on the host (submits and waits), one entry per
/// patch, as the draws read them.
/// \throws osd_cull::Error when the slot is not reserved.
std::vector<PatchTessLevels> readTessLevels(vulkan::Context& context, const GpuPatchSet& gpu,
                                            uint32_t slot);

/// \brief The levels pass's shader variants (both point paths).
std::vector<vulkan::ShaderVariant> tessLevelsPassShaderVariants();

}  // namespace osd_cull::frame
