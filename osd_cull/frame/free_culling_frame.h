#pragma once
/// \file free_culling_frame.h
/// \brief The free-culling frame (DESIGN.md, "Truth and measurement"): the same frame as a
/// culled one, drawing in one render pass, from lists prepared on the host, exactly the
/// patches the culled frame drew, with no cull, pyramid or status work. It is the physical
/// limit of culling on a device: a culled frame's overhead is (culled - free) / unculled,
/// and its share of the ideal saving (unculled - culled) / (unculled - free).

#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/handle.h"

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace osd_cull::vulkan {
class DescriptorPool;
}

namespace osd_cull::frame {

/// \brief The patches a two-pass frame drew, from the status of every patch before and
/// after it (VisibilityBuffer::readStatus, shared/visibility_layout.h kStatus*): the first
/// pass drew the ones visible before, the second pass (not in aggressive mode) the newly
/// visible ones. Sorted patch indices.
/// \throws osd_cull::Error when the two status arrays differ in size.
std::vector<uint32_t> patchesDrawnByFrame(std::span<const uint32_t> statusBefore,
                                          std::span<const uint32_t> statusAfter,
                                          bool aggressive);

/// \brief One render pass drawing given patches of several patch sets.
class FreeCullingFrame {
 public:
  /// \brief For the draws `patches` (their sets are ignored: the frame draws from its own
  /// lists); the patch sets must outlive the frame.
  FreeCullingFrame(vulkan::Context& context, Renderer& renderer,
                   std::span<const PatchDraw> patches);
  ~FreeCullingFrame();
  FreeCullingFrame(const FreeCullingFrame&) = delete;
  FreeCullingFrame& operator=(const FreeCullingFrame&) = delete;

  /// \brief The patches of draw `draw` the next frames draw (indices into its patch set).
  /// \throws osd_cull::Error for an index past the set's patches or a draw out of range.
  void setPatches(size_t draw, std::span<const uint32_t> patches);
  /// \brief Draws the occluders and the chosen patches into `target` in one submission and
  /// waits (Renderer::renderWith); FrameStats::patchesDrawn counts the chosen patches.
  FrameStats render(RenderTarget& target, const Camera& camera,
                    std::span<const GpuTriangleMesh* const> occluders,
                    const RenderOptions& options);

 private:
  struct List {
    vulkan::Buffer entries;  // Bézier from slot 0, Gregory from firstGregorySlot()
    VkDescriptorSet set = VK_NULL_HANDLE;
    uint32_t bezier = 0, gregory = 0;
  };
  vulkan::Context& context_;
  Renderer& renderer_;
  std::vector<PatchDraw> draws_;
  std::vector<List> lists_;
  vulkan::UniqueDescriptorSetLayout setLayout_;
  std::unique_ptr<vulkan::DescriptorPool> pool_;
};

}  // namespace osd_cull::frame
