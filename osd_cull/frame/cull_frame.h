#pragma once
/// \file cull_frame.h
/// \brief The two-pass frame of Niessner & Loop §3 (Fig. 2) for one view over several patch
/// meshes and triangle occluders:
///   1. draw the occluders and the patches visible last frame            → depth
///   2. build the Hi-Z pyramid from that depth (one dispatch, hiz_pyramid.h)
///   3. cull every patch (one dispatch of the cull kernel per patch set, covering all its
///      instances, cull_pass.h: frustum, back-patch, Hi-Z occlusion), update each
///      instance's status, build the draw lists
///   4. draw the patches that became visible                             → final image
/// The aggressive mode (§3.1) skips 4: patches that become visible appear one frame late.
/// Each mesh keeps its own VisibilityBuffer for this view, so another CullFrame (a second
/// camera) can share the meshes.
///
/// The whole frame is recorded into one command buffer, with barriers between the passes
/// and no host wait: record() puts it into the application's command buffer and never
/// submits; render() records it into one command buffer of the Context, submits once and
/// waits. The statistics of a frame are copied on the GPU into a ring of readback slots
/// and read with stats() frames later, without stalling.
///
/// Draws are either compact indirect draws of the listed patches (Filtered) or the paper's
/// variant (§5, TessFactorZero): every patch drawn, the ones not to be drawn with
/// tessellation factors 0. Both give the same image; pipeline statistics tell the cost.

#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/frame/hiz/hiz_cull_stage.h"
#include "osd_cull/frame/hiz/hiz_pyramid.h"
#include "osd_cull/frame/hiz/visibility_buffer.h"
#include "osd_cull/vk/query.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace osd_cull::frame {

/// \brief How the passes draw the patches.
enum class CullDrawMode {
  Filtered,        ///< compact draw lists, vkCmdDrawIndirectCount
  TessFactorZero,  ///< all patches, tessellation factors 0 for the ones not drawn (§5)
};

/// \brief "filtered", "tf0".
const char* toString(CullDrawMode mode);

/// \brief Options of a CullFrame.
struct CullFrameOptions {
  RenderOptions render;  ///< tessellation, colors (clear is set per pass)
  /// The stages of the cull kernel: by default frustum and Hi-Z occlusion ("hiz"); a
  /// back-patch method runs where `cull.backPatchValidity` allows it. With no stage at all
  /// nothing is culled (every patch survives).
  CullSettings cull{true, "", "hiz", {false, "mesh validity not given"}};
  bool aggressive = false;  ///< skip the second pass (§3.1)
  CullDrawMode drawMode = CullDrawMode::Filtered;
  FirstFrame firstFrame = FirstFrame::AllVisible;
  HiZOptions hiz;
  /// Diagnostic mode: render() submits each pass on its own, waits for it and times it
  /// with the wall clock (CullFrameStats::pass1Ms, pyramidMs, cullMs, pass2Ms). Off: the
  /// normal path, one submission per frame, timed per stage by timestamps
  /// (CullFrameStats::gpu).
  bool timePasses = false;
  /// Timestamp queries between the stages of every frame (CullFrameStats::gpu), where the
  /// queue has timestamps. Off, or without them: the times are NaN with the reason in
  /// CullFrameStats::gpuNote.
  bool gpuTimes = true;
  /// Instances sharing a patch set (the same GpuPatchSet, host PatchSet, cull data,
  /// back-patch validity and displacement) are culled by one CullPass: one dispatch per
  /// view for all of them (issue 10), each keeping its own status. False: a pass per
  /// instance (the frame before instancing, kept for comparison).
  bool batchInstances = true;
  /// Slots of the statistics ring: the statistics of frame N can be read with stats(N)
  /// until frame N + statsSlots is recorded. At least the application's frames in flight.
  uint32_t statsSlots = 3;
};

/// \brief GPU time of each stage of one frame (ms), from timestamps written between the
/// stages in the frame's command buffer: pass 1 (its draw commands and the first render
/// pass), the pyramid build, the cull (kernels, status update, draw lists, statistics copy),
/// pass 2. NaN where not measured (see CullFrameStats::gpuNote).
struct CullStageTimes {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  double pass1 = kNone, pyramid = kNone, cull = kNone, pass2 = kNone;
  double total = kNone;  ///< first timestamp to last: the sum of the four
  bool measured() const { return !std::isnan(total); }
};

/// \brief What one frame did.
struct CullFrameStats {
  uint32_t patchesTotal = 0;
  uint32_t drawnPass1 = 0;  ///< patches visible last frame (drawn before the pyramid)
  uint32_t drawnPass2 = 0;  ///< newly visible patches drawn after the cull (0 if aggressive)
  uint32_t survivors = 0;   ///< patches not culled this frame
  uint32_t newlyVisible = 0;
  uint32_t culledFrustum = 0;
  uint32_t culledBackPatch = 0;
  uint32_t culledOcclusion = 0;
  uint32_t culled() const { return culledFrustum + culledBackPatch + culledOcclusion; }
  vulkan::PipelineStatistics pass1;  ///< over the first render pass (occluders included)
  vulkan::PipelineStatistics pass2;
  uint64_t frame = 0;    ///< the number record() returned
  double frameMs = 0.0;  ///< render(): wall clock of recording, submission(s) and wait
  /// Diagnostic mode only (CullFrameOptions::timePasses), else 0: wall clock of each
  /// pass's own submission (record, submit, wait).
  double pass1Ms = 0.0;
  double pyramidMs = 0.0;
  double cullMs = 0.0;  ///< cull kernel and visibility update
  double pass2Ms = 0.0;
  double totalMs() const { return frameMs; }
  /// Timestamps of the stages, in the normal path and the diagnostic mode alike (there
  /// gpu.total includes the host's time between the submissions).
  CullStageTimes gpu;
  std::string gpuNote;  ///< empty when `gpu` was measured, else why it was not
  /// With CullSettings::clusters: what the cluster tests decided (CullPass::clusterCounts,
  /// summed over the meshes' passes; as of the last completed pass).
  ClusterCounts clusters;
};

/// \brief The three stages of a cull kernel, as CullSettings names them.
struct CullStages {
  bool frustum = false;
  std::string backPatch;  ///< a back-patch method; empty: none
  std::string occlusion;  ///< "hiz" or a displaced kernel; empty: none
  bool any() const { return frustum || !backPatch.empty() || !occlusion.empty(); }
  bool operator==(const CullStages&) const = default;
};

/// \brief One patch mesh (or instance) of the scene. Both must outlive the CullFrame.
/// Several CullMeshes may share one GpuPatchSet with different models: the instances of a
/// mesh, each with its own status and culled with view · model composed in double.
struct CullMesh {
  GpuPatchSet* gpu = nullptr;
  const PatchSet* host = nullptr;
  /// The cone methods' per-patch cull data recomputed on the GPU for a moving mesh
  /// (DynamicPatchMesh::cullData, bounds_pass.h), of the frame's back-patch method; null:
  /// built once on the host (static mesh). Must outlive the CullFrame.
  const vulkan::Buffer* cullData = nullptr;
  glm::dmat4 model{1.0};  ///< object → world (instanceCamera()); setModel() changes it
  /// Back-patch validity of this mesh, instead of CullFrameOptions::cull's (a scene's meshes
  /// differ: closed or not, static or deforming).
  std::optional<bound::BackPatchValidity> backPatchValidity;
  /// Whether the draws of this mesh cull back-facing triangles (PatchDraw::cullBackFaces),
  /// instead of CullFrameOptions::render's: a scene culls them per mesh, from the mesh's
  /// own validity, in every mode.
  std::optional<bool> cullBackFaces;
  /// A displaced mesh (its GpuPatchSet draws with the map), instead of
  /// CullFrameOptions::cull's: the map and uvCorners (borrowed) and the displaced bound
  /// the frustum and occlusion stages test (CullSettings::displacementMap).
  const bound::DisplacementMap* displacementMap = nullptr;
  std::span<const glm::dvec2> uvCorners;
  CullMethod::Displaced displacedKernel;
  /// The cull stages of this mesh, instead of CullFrameOptions::cull's frustum, backPatch
  /// and occlusion (a scene's effect plan chooses them per instance): instances batch only
  /// with instances of the same stages, one with no stage is drawn unculled, and the frame
  /// builds its Hi-Z pyramid when any mesh has an occlusion stage.
  std::optional<CullStages> stages;
};

/// \brief The frame pipeline of one view.
class CullFrame {
 public:
  /// \brief Status buffers and a cull pass for every mesh (initialized by
  /// options.firstFrame) and, with occlusion, a pyramid over `target`'s depth. `renderer`,
  /// `target` and the meshes must outlive the frame.
  /// \throws osd_cull::Error for unknown cull methods (see CullPass).
  CullFrame(vulkan::Context& context, Renderer& renderer, RenderTarget& target,
            std::span<const CullMesh> meshes, const CullFrameOptions& options);
  ~CullFrame();
  CullFrame(const CullFrame&) = delete;
  CullFrame& operator=(const CullFrame&) = delete;

  /// \brief Renders one frame into the target and waits for it: record() into one command
  /// buffer, one submission (CullFrameOptions::timePasses: one per pass), then stats().
  /// The item buffer holds itemBase(m) + p + 1 for patch p of mesh m, kItemOccluder for
  /// occluders.
  CullFrameStats render(const Camera& camera, std::span<const GpuTriangleMesh* const> occluders);

  /// \brief Records one whole frame into `cmd` and returns its number for stats(). Never
  /// submits and never waits.
  ///
  /// `cmd` is a primary command buffer in the recording state, outside any render pass,
  /// to be submitted to the Context's queue. The recorded commands:
  /// - start with barriers that wait for every earlier command of the queue that used the
  ///   frame's buffers (patch points written by a deformer included) and the pyramid;
  /// - begin the target's clear pass (color, item and depth images: any previous layout,
  ///   contents discarded) and later its load pass, and leave the images in the target's
  ///   resting layouts (own targets: color TRANSFER_SRC_OPTIMAL, items GENERAL, depth
  ///   DEPTH_STENCIL_ATTACHMENT_OPTIMAL; an application's: ExternalTarget::colorLayout and
  ///   depthLayout), with their writes made available (the render passes' external
  ///   dependencies, or the barriers of dynamic rendering, docs/integration.md);
  /// - move the depth image to TRANSFER_SRC_OPTIMAL (the pyramid build copies it when it
  ///   has TRANSFER_SRC usage) or DEPTH_STENCIL_READ_ONLY_OPTIMAL for the pyramid build and
  ///   back; the pyramid image stays in GENERAL;
  /// - copy the frame's statistics into a readback slot, made available to the host.
  ///
  /// Contract: submit every recorded frame exactly once, in the order recorded (the status
  /// of each patch is carried from frame to frame on the GPU); frame N must have finished
  /// on the device before frame N + statsSlots is recorded. The meshes, occluders and the
  /// target must stay alive until the frame has finished.
  /// \throws osd_cull::Error when the camera's viewport differs from the target's size or
  /// frame N - statsSlots has not finished.
  uint64_t record(VkCommandBuffer cmd, const Camera& camera,
                  std::span<const GpuTriangleMesh* const> occluders);

  /// \brief The statistics of frame `frame` (a number record() returned) without waiting:
  /// std::nullopt while the device has not finished the frame, or once its slot has been
  /// reused (frame + statsSlots was recorded). Read them after the application has waited
  /// for the frame's submission (its fence), typically statsSlots - 1 frames later.
  std::optional<CullFrameStats> stats(uint64_t frame) const;

  /// \brief Starts over as before the first frame (e.g. after a camera cut).
  void reset(FirstFrame firstFrame);

  const CullFrameOptions& options() const { return options_; }
  /// \brief Changes tessellation, draw mode or aggressiveness between frames (the cull
  /// stages, the pyramid options and the first-frame policy are fixed at construction).
  void setOptions(const CullFrameOptions& options);
  /// \brief True when the Hi-Z occlusion stage runs (a pyramid exists).
  bool occlusion() const { return pyramid_ != nullptr; }
  /// \throws osd_cull::Error without occlusion.
  const HiZPyramid& pyramid() const;
  /// \brief The cull pass of `mesh` (shared by the instances of its patch set, see
  /// CullFrameOptions::batchInstances), or nullptr when no stage is enabled.
  const CullPass* cullPass(size_t mesh) const { return batches_.at(batchOf_.at(mesh)).pass.get(); }
  /// \brief Mesh `mesh`'s instance index in its cullPass().
  uint32_t instanceInPass(size_t mesh) const { return slotOf_.at(mesh); }
  /// \brief Cull passes: one per patch set (one per mesh without batchInstances).
  size_t cullPassCount() const { return batches_.size(); }
  /// \brief Cull dispatches recorded since construction, all passes.
  uint64_t cullDispatches() const;
  size_t meshCount() const { return meshes_.size(); }
  /// \brief Moves mesh `mesh` (an instance) for the next frames.
  void setModel(size_t mesh, const glm::dmat4& model) { meshes_.at(mesh).model = model; }
  const glm::dmat4& model(size_t mesh) const { return meshes_.at(mesh).model; }
  VisibilityBuffer& visibility(size_t mesh) { return *visibility_.at(mesh); }
  uint32_t itemBase(size_t mesh) const { return itemBases_.at(mesh); }
  /// \brief Result codes of the last cull (one per patch of `mesh`), read back.
  std::vector<uint32_t> readResults(size_t mesh) const;

  /// \brief The debug view: every patch drawn from `camera` into `target`, colored by its
  /// status after the last frame (draw_layout.h kDrawStatus*: visible, newly visible,
  /// culled by frustum, back-patch or occlusion), with the occluders.
  FrameStats renderStatusView(RenderTarget& target, const Camera& camera,
                              std::span<const GpuTriangleMesh* const> occluders);

 private:
  struct Chunks {
    uint32_t bezier = 1, gregory = 1;
  };
  struct StatsSlot;
  Chunks chunks(size_t mesh) const;
  void recordPatchDraws(VkCommandBuffer cmd, const Camera& camera, bool secondPass);
  void recordMeshDraws(VkCommandBuffer cmd, const Camera& camera, size_t mesh, bool secondPass);
  StatsSlot& beginFrame(const Camera& camera);
  void recordFirstPass(VkCommandBuffer cmd, const Camera& camera,
                       std::span<const GpuTriangleMesh* const> occluders, StatsSlot& slot);
  void recordPyramid(VkCommandBuffer cmd, StatsSlot& slot);
  void recordCull(VkCommandBuffer cmd, const Camera& camera, StatsSlot& slot);
  void recordSecondPass(VkCommandBuffer cmd, const Camera& camera, StatsSlot& slot);

  vulkan::Context& context_;
  Renderer& renderer_;
  RenderTarget& target_;
  std::vector<CullMesh> meshes_;
  CullFrameOptions options_;
  std::vector<uint32_t> itemBases_;
  std::unique_ptr<VisibilityPrograms> programs_;
  std::vector<std::unique_ptr<VisibilityBuffer>> visibility_;
  // The meshes culled by one pass (one dispatch): the instances of a patch set.
  struct Batch {
    std::unique_ptr<CullPass> pass;  // null when no stage is enabled
    std::vector<size_t> members;     // mesh indices, in the pass's instance order
    // With several members: each one's result codes, copied from the pass's shared buffer
    // for its VisibilityBuffer update.
    std::vector<vulkan::Buffer> results;
  };
  void recordBatchCull(VkCommandBuffer cmd, const Camera& camera, Batch& batch);
  std::vector<Batch> batches_;
  std::vector<size_t> batchOf_;        // per mesh
  std::vector<uint32_t> slotOf_;       // per mesh: its instance in the batch
  std::vector<uint32_t> levelSlotOf_;  // per mesh: its slot of its set's tessLevels()
  vulkan::Buffer survivedResults_;     // all kStageNone, used without a pass
  std::unique_ptr<HiZPyramid> pyramid_;
  std::unique_ptr<HiZCullStage> stage_;
  std::vector<std::unique_ptr<StatsSlot>> slots_;  // the statistics ring
  std::string gpuNote_;  // why the slots have no timestamps; empty when they have
  uint64_t nextFrame_ = 0;
  std::vector<vulkan::Buffer> statusLists_;  // debug view lists, made on first use
  std::vector<VkDescriptorSet> statusSets_;
  vulkan::UniqueDescriptorSetLayout statusSetLayout_;
  std::unique_ptr<vulkan::DescriptorPool> statusPool_;
};

}  // namespace osd_cull::frame
