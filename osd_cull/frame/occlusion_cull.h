#pragma once
/// \file occlusion_cull.h
/// \brief The Hi-Z occlusion test of every patch of a GpuPatchSet against a HiZPyramid, on
/// its own (shaders/hiz/occlusion_cull.comp), writing one result code per patch in the cull
/// kernel's layout (shared/hiz_layout.h kOcclusion*, shared/visibility_layout.h kResult*).
/// The frame's cull kernel runs the same GLSL functions (shaders/hiz/occlusion.glsl)
/// behind its frustum and back-patch tests.

#include "osd_cull/frame/camera.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/pipeline.h"

#include <cstdint>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

namespace osd_cull::vk {
class Context;
class DescriptorPool;
}  // namespace osd_cull::vk

namespace osd_cull::frame {

class GpuPatchSet;
class HiZPyramid;

/// \brief One patch's result, decoded.
struct OcclusionCullResult {
  bool tested = false;  ///< every w > 0 and the box is on screen
  bool culled = false;
  uint32_t level = 0;  ///< pyramid level of the footprint (when tested)
};

/// \brief Decodes a result code of the kernel.
OcclusionCullResult decodeOcclusionResult(uint32_t code);

/// \brief Runs the occlusion-only kernel.
class OcclusionCullKernel {
 public:
  explicit OcclusionCullKernel(vk::Context& context);
  ~OcclusionCullKernel();

  /// \brief Records the test of every patch of `patches` for `camera` against `pyramid`
  /// (built earlier in the command buffer or before) into `results` (4 bytes per patch),
  /// followed by a barrier to compute reads and transfers. The camera's viewport must match
  /// the pyramid's depth image; the buffers must outlive the command buffer.
  void record(VkCommandBuffer cmd, const GpuPatchSet& patches, const Camera& camera,
              const HiZPyramid& pyramid, const vk::Buffer& results);

  /// \brief record() in its own submission; waits and returns the decoded results.
  std::vector<OcclusionCullResult> run(const GpuPatchSet& patches, const Camera& camera,
                                       const HiZPyramid& pyramid);

 private:
  VkDescriptorSet set(const GpuPatchSet& patches, const HiZPyramid& pyramid,
                      const vk::Buffer& results);

  vk::Context& context_;
  std::unique_ptr<vk::ComputeProgram> program_;
  std::unique_ptr<vk::DescriptorPool> pool_;
  std::map<std::tuple<VkBuffer, VkImageView, VkBuffer>, VkDescriptorSet> sets_;
  uint32_t allocated_ = 0;
};

}  // namespace osd_cull::frame
