#include "osd_cull/frame/free_culling_frame.h"

#include "osd_cull/error.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/transfer.h"

#include <osd_cull/shared/draw_layout.h>
#include <osd_cull/shared/visibility_layout.h>

#include <algorithm>

namespace osd_cull::frame {

std::vector<uint32_t> patchesDrawnByFrame(std::span<const uint32_t> statusBefore,
                                          std::span<const uint32_t> statusAfter,
                                          bool aggressive) {
  if (statusBefore.size() != statusAfter.size())
    throw Error("patchesDrawnByFrame: " + std::to_string(statusBefore.size()) +
                " statuses before the frame, " + std::to_string(statusAfter.size()) + " after");
  std::vector<uint32_t> drawn;
  for (uint32_t p = 0; p < statusBefore.size(); ++p) {
    const bool first = (statusBefore[p] & shader::kStatusVisible) != 0u;
    const bool second = !aggressive && (statusAfter[p] & shader::kStatusNewlyVisible) != 0u;
    if (first || second) drawn.push_back(p);
  }
  return drawn;
}

FreeCullingFrame::FreeCullingFrame(vulkan::Context& context, Renderer& renderer,
                                   std::span<const PatchDraw> patches)
    : context_(context), renderer_(renderer), draws_(patches.begin(), patches.end()) {
  setLayout_ = vulkan::createDescriptorSetLayout(context, patchSetBindings());
  pool_ = std::make_unique<vulkan::DescriptorPool>(
      context, static_cast<uint32_t>(std::max<size_t>(1, draws_.size())), patchSetBindings());
  for (const PatchDraw& d : draws_) {
    if (!d.gpu) throw Error("FreeCullingFrame: a draw without a GpuPatchSet");
    List list;
    list.entries = vulkan::Buffer(context, std::max<size_t>(4, size_t{d.gpu->patchCount()} * 4),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    list.set = pool_->allocate(setLayout_.get());
    d.gpu->writeDescriptorSet(context.device(), list.set, list.entries);
    lists_.push_back(std::move(list));
  }
}

FreeCullingFrame::~FreeCullingFrame() = default;

void FreeCullingFrame::setPatches(size_t draw, std::span<const uint32_t> patches) {
  if (draw >= draws_.size())
    throw Error("FreeCullingFrame::setPatches: draw " + std::to_string(draw) + " of " +
                std::to_string(draws_.size()));
  const GpuPatchSet& g = *draws_[draw].gpu;
  List& list = lists_[draw];
  // The layout of a cull pass's list: Bézier entries from slot 0, Gregory ones from the
  // first Gregory slot, each the patch index with the status "visible".
  std::vector<uint32_t> entries(std::max<size_t>(1, g.patchCount()), 0u);
  list.bezier = list.gregory = 0;
  for (uint32_t p : patches) {
    if (p >= g.patchCount())
      throw Error("FreeCullingFrame::setPatches: patch " + std::to_string(p) + " of a set of " +
                  std::to_string(g.patchCount()));
    const uint32_t entry = p | (shader::kDrawStatusVisible << shader::kDrawListStatusShift);
    if (p < g.firstGregorySlot())
      entries[list.bezier++] = entry;
    else
      entries[g.firstGregorySlot() + list.gregory++] = entry;
  }
  vulkan::upload<uint32_t>(context_, list.entries, entries);
}

FrameStats FreeCullingFrame::render(RenderTarget& target, const Camera& camera,
                                    std::span<const GpuTriangleMesh* const> occluders,
                                    const RenderOptions& options) {
  uint32_t patches = 0;
  FrameStats stats = renderer_.renderWith(
      target, camera, occluders, options, [](VkCommandBuffer) {},
      [&](VkCommandBuffer cmd) {
        uint32_t calls = 0;
        for (size_t d = 0; d < draws_.size(); ++d) {
          PatchDraw draw = draws_[d];
          draw.set = lists_[d].set;
          const List& l = lists_[d];
          if (l.bezier > 0)
            calls += renderer_.recordSlots(cmd, camera, draw, PatchType::Bezier, 0, l.bezier, {},
                                           options);
          if (l.gregory > 0)
            calls += renderer_.recordSlots(cmd, camera, draw, PatchType::Gregory,
                                           draw.gpu->firstGregorySlot(), l.gregory, {}, options);
          patches += l.bezier + l.gregory;
        }
        return calls;
      });
  stats.patchesDrawn = patches;
  return stats;
}

}  // namespace osd_cull::frame
