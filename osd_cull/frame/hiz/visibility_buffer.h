#pragma once
/// \file visibility_buffer.h
/// \brief Per-mesh, per-view visibility status on the GPU and the draw lists built from it
/// (Niessner & Loop §3 and §5): each patch is VISIBLE (drawn in the first pass of the next
/// frame), NEWLY VISIBLE (drawn in this frame's second pass) or culled (with the stage that
/// culled it).
///
/// A frame uses it as: recordFirstPassCommands() before the first pass draws firstPass();
/// the cull kernel writes one result per patch into a results buffer; recordUpdate() turns
/// the results into new status bits, the second-pass list and the next frame's first-pass
/// list; the second pass draws secondPass(); advance() makes the new first-pass list
/// current. The tess-factor-0 variant draws firstPassAll() / secondPassAll() instead: every
/// patch, with the culled flag on the patches not to be drawn.

#include "osd_cull/frame/draw/gpu_patch_set.h"
#include "osd_cull/frame/draw/tess_levels.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/pipeline.h"

#include <osd_cull/shared/visibility_layout.h>

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <vector>

namespace osd_cull::vulkan {
class Context;
class DescriptorPool;
}  // namespace osd_cull::vulkan

namespace osd_cull::frame {

/// \brief Status of every patch before the first frame (§3: "we mark half of the patches as
/// visible and the other half occluded").
enum class FirstFrame {
  AllVisible,   ///< the first pass draws everything (the simplest start)
  HalfVisible,  ///< even patch indices visible, odd occluded (the paper's split)
  NoneVisible,  ///< the first pass draws only occluders; the second pass the survivors
};

/// \brief "all", "half", "none".
const char* toString(FirstFrame policy);

/// \brief The compute programs of the visibility pass, shared by every VisibilityBuffer.
class VisibilityPrograms {
 public:
  explicit VisibilityPrograms(vulkan::Context& context);
  ~VisibilityPrograms();
  const vulkan::ComputeProgram& update() const { return *update_; }
  const vulkan::ComputeProgram& draws() const { return *draws_; }

 private:
  std::unique_ptr<vulkan::ComputeProgram> update_;
  std::unique_ptr<vulkan::ComputeProgram> draws_;
};

/// \brief A compact draw list with its counters (shared/visibility_layout.h kList*) and
/// indirect draw commands (Bezier first, then Gregory).
struct DrawListBuffers {
  vulkan::Buffer list;      ///< patch entries (draw_layout.h kDrawList*)
  vulkan::Buffer counters;  ///< host-visible: survivors and draw counts per type
  vulkan::Buffer commands;  ///< VkDrawIndirectCommand, maxBezierDraws + maxGregoryDraws
  VkDescriptorSet drawSet = VK_NULL_HANDLE;  ///< the patch set's descriptors with `list`
  VkDescriptorSet draws = VK_NULL_HANDLE;    ///< visibility_draws.comp over counters, commands
  /// \brief Survivors per type as last written (read after the frame's submission).
  uint32_t bezier() const;
  uint32_t gregory() const;
};

/// \brief Status buffer and draw lists of one mesh in one view.
class VisibilityBuffer {
 public:
  VisibilityBuffer(vulkan::Context& context, const VisibilityPrograms& programs, GpuPatchSet& gpu,
                   FirstFrame firstFrame);
  ~VisibilityBuffer();
  VisibilityBuffer(const VisibilityBuffer&) = delete;
  VisibilityBuffer& operator=(const VisibilityBuffer&) = delete;

  GpuPatchSet& patches() const { return gpu_; }
  uint32_t patchCount() const { return gpu_.patchCount(); }

  /// \brief Sets every status and the first-pass lists for `firstFrame` (uploads, waits).
  void reset(FirstFrame firstFrame);

  /// \brief Records visibility_draws.comp over the current first-pass list with draws of at
  /// most `chunkBezier` / `chunkGregory` patches, and barriers to indirect draws.
  void recordFirstPassCommands(VkCommandBuffer cmd, uint32_t chunkBezier, uint32_t chunkGregory);
  /// \brief Records: counter reset, visibility_update.comp over `results` (one result code
  /// per patch, written by the cull kernel earlier in the command buffer: the caller makes
  /// them visible to compute reads), the second-pass draw commands, and barriers to
  /// indirect draws, draw shaders and the host.
  void recordUpdate(VkCommandBuffer cmd, const vulkan::Buffer& results, uint32_t chunkBezier,
                    uint32_t chunkGregory);
  /// \brief uints per mesh that recordStatsCopy() writes: the first-pass list counters
  /// (kList*), then the statistics of the update (kStat*).
  static constexpr uint32_t kStatsCopyWords = shader::kListCounterCount + shader::kStatCount;
  /// \brief Records copies of the current first-pass counters and of the statistics of the
  /// last recordUpdate() into `dst` at byte `offset` (kStatsCopyWords uints), after the
  /// update in the same command buffer; the copy is made available to the host.
  void recordStatsCopy(VkCommandBuffer cmd, const vulkan::Buffer& dst, VkDeviceSize offset);
  /// \brief Begins conditional rendering (VK_EXT_conditional_rendering) on the
  /// newly-visible count of the last recordUpdate(): the draws recorded until
  /// endCondition() are skipped on the device when no patch became newly visible. Returns
  /// false and records nothing without OptionalFeatures::conditionalRendering.
  bool beginIfNewlyVisible(VkCommandBuffer cmd) const;
  /// \brief Ends what beginIfNewlyVisible() began (only after it returned true).
  void endCondition(VkCommandBuffer cmd) const;
  /// \brief After the frame: the list built by recordUpdate() becomes the first-pass list.
  void advance() { parity_ ^= 1u; }

  DrawListBuffers& firstPass() { return lists_[parity_]; }
  DrawListBuffers& secondPass() { return secondPass_; }
  /// \brief Full lists of the tess-factor-0 variant (slot = patch index).
  VkDescriptorSet firstPassAll() const { return allSets_[parity_]; }
  VkDescriptorSet secondPassAll() const { return secondAllSet_; }
  uint32_t maxDraws(PatchType type, uint32_t chunk) const;

  /// \brief Statistics counters of the last update (kStat*), host-visible.
  std::span<const uint32_t> stats() const;
  /// \brief The status of every patch (shared/visibility_layout.h kStatus*), read back.
  std::vector<uint32_t> readStatus(vulkan::Context& context) const;

 private:
  VkDescriptorSet updateSet(const vulkan::Buffer& results);

  vulkan::Context& context_;
  const VisibilityPrograms& programs_;
  GpuPatchSet& gpu_;
  uint32_t parity_ = 0;
  bool conditional_ = false;  // the second pass's draws are conditional on stats_
  vulkan::Buffer status_;
  vulkan::Buffer stats_;
  std::array<DrawListBuffers, 2> lists_;  // first-pass lists: current and next
  DrawListBuffers secondPass_;
  std::array<vulkan::Buffer, 2> all_;  // tess-factor-0 lists, first pass: current and next
  vulkan::Buffer secondAll_;
  std::array<VkDescriptorSet, 2> allSets_{};
  VkDescriptorSet secondAllSet_ = VK_NULL_HANDLE;
  std::unique_ptr<vulkan::DescriptorPool> pool_;
  vulkan::UniqueDescriptorSetLayout drawSetLayout_;  // patchSetBindings(), for the draw sets
  std::unique_ptr<vulkan::DescriptorPool> drawPool_;
  std::map<std::pair<VkBuffer, uint32_t>, VkDescriptorSet> updateSets_;  // (results, parity)
};

}  // namespace osd_cull::frame
