#pragma once
/// \file cull_frame.h
/// \brief The two-pass frame of Niessner & Loop §3 (Fig. 2) for one view over several patch
/// meshes and triangle occluders:
///   1. draw the occluders and the patches visible last frame            → depth
///   2. build the Hi-Z pyramid from that depth
///   3. cull every patch (one dispatch of the cull kernel, cull_pass.h: frustum, back-patch,
///      Hi-Z occlusion), update its status, build the draw lists
///   4. draw the patches that became visible                             → final image
/// The aggressive mode (§3.1) skips 4: patches that become visible appear one frame late.
/// Each mesh keeps its own VisibilityBuffer for this view, so another CullFrame (a second
/// camera) can share the meshes.
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

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
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
  double pass1Ms = 0.0;  ///< wall clock of each submission (record, submit, wait)
  double pyramidMs = 0.0;
  double cullMs = 0.0;  ///< cull kernel and visibility update
  double pass2Ms = 0.0;
  double totalMs() const { return pass1Ms + pyramidMs + cullMs + pass2Ms; }
};

/// \brief One patch mesh (or instance) of the scene. Both must outlive the CullFrame.
/// Several CullMeshes may share one GpuPatchSet with different models: the instances of a
/// mesh, each with its own status and culled with view · model composed in double.
struct CullMesh {
  GpuPatchSet* gpu = nullptr;
  const PatchSet* host = nullptr;
  glm::dmat4 model{1.0};  ///< object → world (instanceCamera()); setModel() changes it
  /// Back-patch validity of this mesh, instead of CullFrameOptions::cull's (a scene's meshes
  /// differ: closed or not, static or deforming).
  std::optional<bound::BackPatchValidity> backPatchValidity;
  /// The cone methods' per-patch cull data recomputed on the GPU for a moving mesh
  /// (DynamicPatchMesh::cullData, bounds_pass.h), of the frame's back-patch method; null:
  /// built once on the host (static mesh). Must outlive the CullFrame.
  const vulkan::Buffer* cullData = nullptr;
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

  /// \brief Renders one frame into the target; the item buffer holds itemBase(m) + p + 1
  /// for patch p of mesh m, kItemOccluder for occluders.
  CullFrameStats render(const Camera& camera, std::span<const GpuTriangleMesh* const> occluders);

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
  /// \brief The cull pass of `mesh`, or nullptr when no stage is enabled.
  const CullPass* cullPass(size_t mesh) const { return passes_.at(mesh).get(); }
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
  Chunks chunks(size_t mesh) const;
  void recordPatchDraws(VkCommandBuffer cmd, const Camera& camera, bool secondPass);

  vulkan::Context& context_;
  Renderer& renderer_;
  RenderTarget& target_;
  std::vector<CullMesh> meshes_;
  CullFrameOptions options_;
  std::vector<uint32_t> itemBases_;
  std::unique_ptr<VisibilityPrograms> programs_;
  std::vector<std::unique_ptr<VisibilityBuffer>> visibility_;
  std::vector<std::unique_ptr<CullPass>> passes_;  // null when no stage is enabled
  vulkan::Buffer survivedResults_;                 // all kStageNone, used without a pass
  std::unique_ptr<HiZPyramid> pyramid_;
  std::unique_ptr<HiZCullStage> stage_;
  vulkan::PipelineStatisticsQuery queries_;
  std::vector<vulkan::Buffer> statusLists_;  // debug view lists, made on first use
  std::vector<VkDescriptorSet> statusSets_;
  vulkan::UniqueDescriptorSetLayout statusSetLayout_;
  std::unique_ptr<vulkan::DescriptorPool> statusPool_;
};

}  // namespace osd_cull::frame
