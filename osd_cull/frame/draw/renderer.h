#pragma once
/// \file renderer.h
/// \brief Draws tessellated Bézier and Gregory patches (and triangle occluders) into a
/// RenderTarget, with pipeline statistics and timing per frame.

#include "osd_cull/frame/camera.h"
#include "osd_cull/frame/draw/draw_chunks.h"
#include "osd_cull/frame/draw/gpu_patch_set.h"
#include "osd_cull/frame/draw/render_target.h"
#include "osd_cull/frame/draw/tess_levels.h"
#include "osd_cull/frame/draw/tess_levels_pass.h"
#include "osd_cull/frame/draw/triangle_mesh.h"
#include "osd_cull/vk/pipeline.h"
#include "osd_cull/vk/query.h"

#include <glm/vec3.hpp>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <tuple>

namespace osd_cull::frame {

/// \brief Options of one frame.
struct RenderOptions {
  TessellationOptions tessellation;
  /// Split patch draws by tessellated vertex count (draw_chunks.h). Off only to measure
  /// what the lavapipe batching bug does.
  bool chunkDraws = true;
  /// Color each patch by a hash of its index instead of one material color.
  bool debugColors = false;
  /// Color each patch by the status field of its draw-list entry (kDrawStatus* in
  /// shaders/shared/draw_layout.h): the debug view of the cull frame.
  bool statusColors = false;
  /// Color each patch by its type: regular, boundary (one boundary edge), corner (two or
  /// more), Gregory (the viewer's patch-type view, as OpenSubdiv's glViewer).
  bool patchTypeColors = false;
  /// Draw the tessellated triangles' edges only (needs fillModeNonSolid). The item buffer
  /// then holds the lines: for viewing, not for the oracle.
  bool wireframe = false;
  /// Cull triangles facing away (surface normal dPdu x dPdv pointing away from the eye).
  bool cullBackFaces = false;
  /// Back-facing fragments lose depth ties with front-facing ones: they are pushed back by
  /// one pixel of their depth slope (shaders/patch/patch.frag). Keeps a back face from
  /// winning silhouette-edge pixels, which the item-buffer oracle would count as visible.
  /// Off only to read exact depths of back faces.
  bool frontFacesWinTies = true;
  /// Fragment depth of undisplaced patches is clamped to their nearest control point
  /// (shaders/patch/patch.tesc), which the Hi-Z occlusion bound needs on a rasterizer that
  /// extrapolates depth. Off only to measure what the clamp costs (bench-draw
  /// --depth-clamp-cost): Hi-Z culls are then not proven for what is drawn.
  bool clampDepthToControlPoints = true;
  /// Clear the target first; false draws over its contents (a second pass).
  bool clear = true;
  glm::vec3 background{0.12f, 0.12f, 0.14f};
};

/// \brief One patch set to draw, and where its item-buffer values start.
struct PatchDraw {
  const GpuPatchSet* gpu = nullptr;
  /// Host copy of the same patches: with adaptive tessellation, draws are split by each
  /// patch's own vertex bound; without it, by the bound of the maximum level.
  const PatchSet* host = nullptr;
  /// Patch p writes itemBase + p + 1 into the item buffer.
  uint32_t itemBase = 0;
  /// Descriptor set to draw with instead of gpu->descriptorSet(), e.g. one from
  /// GpuPatchSet::descriptorSetWithDrawList() for a culled draw list.
  VkDescriptorSet set = VK_NULL_HANDLE;
  /// Object → world matrix of this draw (an instance, scene/scene_eval.h); null: identity.
  /// The draw uses instanceCamera(camera, *model), composed in double.
  const glm::dmat4* model = nullptr;
  /// Whether the rasterizer culls this draw's back-facing triangles, instead of
  /// RenderOptions::cullBackFaces (a scene's meshes differ: closed and oriented or not);
  /// unset: the options'.
  std::optional<bool> cullBackFaces;
  /// With adaptive tessellation of an undisplaced set: the draw reads its levels from this
  /// slot of GpuPatchSet::tessLevels(), written for the same camera by a TessLevelsPass
  /// earlier in the command buffer (Renderer::recordTessLevels; render() records it
  /// itself). Unset: the control shader computes the levels (docs/algorithms/
  /// drawn-triangles.md, "Exact adaptive levels": a culled frame then has to draw so too).
  std::optional<uint32_t> tessLevelSlot;
};

/// \brief What one frame did.
struct FrameStats {
  double wallMs = 0.0;  ///< recording, submission and wait, on the host clock
  double gpuMs = 0.0;   ///< timestamps around the render pass (0 without timestamp support)
  uint32_t patchesDrawn = 0;
  uint32_t drawCalls = 0;
  uint32_t occluderTriangles = 0;
  vulkan::PipelineStatistics statistics;  ///< over the whole render pass
};

/// \brief Pipelines and per-frame recording of patch and triangle draws.
///
/// render() records, submits and waits for one frame. The record* functions let a frame
/// pipeline put the same draws into its own command buffer (between beginPass/endPass).
class Renderer {
 public:
  explicit Renderer(vulkan::Context& context);

  /// \brief Draws occluders, then patch sets, into `target` and waits.
  FrameStats render(RenderTarget& target, const Camera& camera, std::span<const PatchDraw> patches,
                    std::span<const GpuTriangleMesh* const> occluders,
                    const RenderOptions& options);
  /// \brief Like render(), with patch draws recorded by the caller: `beforePass` is
  /// recorded before the render pass begins (e.g. a cull dispatch), `recordPatchDraws`
  /// inside it after the occluders, returning its number of draw calls.
  /// FrameStats::patchesDrawn is left 0 for the caller to fill in.
  FrameStats renderWith(RenderTarget& target, const Camera& camera,
                        std::span<const GpuTriangleMesh* const> occluders,
                        const RenderOptions& options,
                        const std::function<void(VkCommandBuffer)>& beforePass,
                        const std::function<uint32_t(VkCommandBuffer)>& recordPatchDraws);
  /// \brief One patch set, no occluders.
  FrameStats render(RenderTarget& target, const Camera& camera, const GpuPatchSet& patches,
                    const PatchSet* host, const RenderOptions& options);

  /// \brief Begins the target's clear or load render pass (or, with dynamic rendering,
  /// moves its images to attachment layouts and begins rendering) and sets viewport and
  /// scissor.
  void beginPass(VkCommandBuffer cmd, RenderTarget& target, const RenderOptions& options) const;
  /// \brief Ends the pass beginPass() began (and returns dynamic-rendering images to the
  /// target's resting layouts).
  void endPass(VkCommandBuffer cmd) const;
  /// \brief For draws the caller records into a pass it began itself (e.g. a subpass of
  /// the application's render pass): the record* functions use pipelines for `format`
  /// until the next beginPass(). Default: an own RenderTarget's default formats.
  void setDrawFormat(const TargetFormat& format) const { drawFormat_ = format; }
  /// \brief Records the levels pass of `draw` for `camera` into slot `slot` (outside a
  /// pass); draws then read them with PatchDraw::tessLevelSlot = slot. Nothing is recorded
  /// when the options or the set do not use it (usesTessLevelsPass()).
  void recordTessLevels(VkCommandBuffer cmd, const Camera& camera, const PatchDraw& draw,
                        uint32_t slot, const RenderOptions& options);
  /// \brief Records triangle occluder draws (inside a pass).
  void recordOccluders(VkCommandBuffer cmd, const Camera& camera,
                       std::span<const GpuTriangleMesh* const> occluders);
  /// \brief Records the draws of all patches of one set (inside a pass); returns the
  /// number of draw calls.
  uint32_t recordPatches(VkCommandBuffer cmd, const Camera& camera, const PatchDraw& draw,
                         const RenderOptions& options);
  /// \brief Records draws of draw-list slots [firstSlot, firstSlot + count) of one patch
  /// type with the given per-slot vertex bounds (empty: bound of the maximum level).
  uint32_t recordSlots(VkCommandBuffer cmd, const Camera& camera, const PatchDraw& draw,
                       PatchType type, uint32_t firstSlot, uint32_t count,
                       std::span<const uint32_t> vertexBounds, const RenderOptions& options);
  /// \brief Records GPU-generated draws of one patch type (inside a pass): `commands`
  /// holds VkDrawIndirectCommand entries {slots * P, 1, firstSlot * P, 0} with P = 16 or
  /// 20; their count is read from `count` at `countOffset` (vkCmdDrawIndirectCount), at
  /// most maxDraws. Whoever writes the commands must keep each within the batch limits of
  /// draw_chunks.h (lavapipe) and make the writes visible to DRAW_INDIRECT before the pass.
  void recordIndirect(VkCommandBuffer cmd, const Camera& camera, const PatchDraw& draw,
                      PatchType type, const vulkan::Buffer& commands, VkDeviceSize offset,
                      const vulkan::Buffer& count, VkDeviceSize countOffset, uint32_t maxDraws,
                      const RenderOptions& options);

 private:
  VkPipeline patchPipeline(PatchType type, bool cullBackFaces, bool wireframe, bool mirrored,
                           bool displaced, const TargetFormat& format);
  VkPipeline trianglePipeline(const TargetFormat& format);
  // Render pass, subpass and formats of pipelines for `format`.
  void describeTarget(vulkan::GraphicsPipelineDesc& d, const TargetFormat& format);
  void bindPatches(VkCommandBuffer cmd, const Camera& camera, const PatchDraw& draw, PatchType type,
                   const RenderOptions& options);

  vulkan::Context& context_;
  // Per own-target format set: a pass compatible with every such RenderTarget's passes.
  std::map<TargetFormat, vulkan::UniqueRenderPass> referencePasses_;
  // The target of the pass being recorded (beginPass → endPass).
  mutable RenderTarget* openTarget_ = nullptr;
  mutable TargetFormat drawFormat_;  // what record* draws for
  vulkan::UniqueDescriptorSetLayout patchSetLayout_;
  vulkan::UniqueDescriptorSetLayout meshSetLayout_;
  vulkan::UniquePipelineLayout patchLayout_;
  vulkan::UniqueDescriptorSetLayout displacementSetLayout_;
  vulkan::UniquePipelineLayout displacedLayout_;  // set 0 patches, set 1 displacement
  vulkan::UniquePipelineLayout meshLayout_;
  std::map<std::tuple<PatchType, bool, bool, bool, bool, TargetFormat>, vulkan::UniquePipeline>
      patchPipelines_;
  std::map<TargetFormat, vulkan::UniquePipeline> trianglePipelines_;
  vulkan::PipelineStatisticsQuery statistics_;
  std::optional<vulkan::TimestampQuery> timestamps_;  // absent when the queue has no timestamps
  std::unique_ptr<TessLevelsPass> tessLevels_;        // made on first use
};

}  // namespace osd_cull::frame
