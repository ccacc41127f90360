#pragma once
/// \file occlusion_cull.h
/// \brief The Hi-Z occlusion test of every patch of a GpuPatchSet against a HiZPyramid, on
/// its own (shaders/hiz/occlusion_cull.comp): per patch whether the test applied, whether
/// the patch is occluded, and the pyramid level used. The frame's cull kernel runs the
/// same GLSL functions (shaders/hiz/occlusion.glsl) behind its frustum and back-patch tests.

#include "osd_cull/frame/camera.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/pipeline.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace osd_cull::vk {
class Context;
class DescriptorPool;
}  // namespace osd_cull::vk

namespace osd_cull::frame {

class GpuPatchSet;
class HiZPyramid;

/// \brief One patch's result (shared/hiz_layout.h kOcclusion*).
struct OcclusionCullResult {
  bool tested = false;  ///< every w > 0 and the box is on screen
  bool culled = false;
  uint32_t level = 0;  ///< pyramid level of the footprint (when tested)
};

/// \brief Runs the occlusion-only kernel.
class OcclusionCullKernel {
 public:
  explicit OcclusionCullKernel(vk::Context& context);
  ~OcclusionCullKernel();

  /// \brief Tests every patch of `patches` for `camera` against the built `pyramid`,
  /// submits and waits. The camera's viewport must match the pyramid's depth image.
  std::vector<OcclusionCullResult> run(const GpuPatchSet& patches, const Camera& camera,
                                       const HiZPyramid& pyramid);

 private:
  vk::Context& context_;
  std::unique_ptr<vk::ComputeProgram> program_;
  std::unique_ptr<vk::DescriptorPool> pool_;
};

}  // namespace osd_cull::frame
