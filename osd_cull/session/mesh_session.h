#pragma once
/// \file mesh_session.h
/// \brief One patch mesh in one view, frame after frame: the frame loop a program runs to draw
/// a mesh culled — by fixed stages, or by the effect plan (docs/algorithms/plan.md) — with
/// the per-stage counts and a summary of the run. `osd-cull render` and `view`, bench-plan,
/// the tests and the samples draw a mesh through it; the scene form has its own player
/// (scene_player.h).
///
/// Each frame the session
///  1. asks the planner for this frame's plan (with one: the mesh's PlanInput, its
///     tessellation level, an adaptive one as the uniform level of the same work,
///     plan::equivalentUniformLevel);
///  2. draws with what the plan (or the fixed options) says: no stage, the plain renderer;
///     frustum and back-patch stages only, one pass with the cull kernel before it
///     (frame::renderCulled); occlusion, the two-pass frame with temporal visibility
///     (frame::CullFrame, Niessner & Loop §3);
///  3. counts each stage's culls the one way (countByStage) and feeds counts and times back
///     (plan::Planner::observe, the cull work timed apart where the frame measured it).
///
/// A plan change never starts the frame over (issue 18): the pass or frame of every
/// configuration used is kept (the last `cachedConfigurations`, least recently used
/// dropped), with its visibility status, so returning to a choice draws from the status it
/// left instead of drawing everything; a configuration met for the first time starts with
/// nothing visible (FirstFrame::NoneVisible: the second pass draws the survivors of the
/// other stages, never every patch). Memory is bounded by the cache.

#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/plan/planner.h"

#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace osd_cull::session {

/// \brief Patches culled by each stage, from one result code per patch (bound::CullCode:
/// a patch counts for the first stage that culled it).
struct StageCounts {
  uint32_t frustum = 0, backPatch = 0, occlusion = 0;
  uint32_t culled() const { return frustum + backPatch + occlusion; }
};
StageCounts countByStage(std::span<const uint32_t> results);

/// \brief How a frame was drawn.
enum class FrameKind {
  Plain,    ///< no cull stage: the plain renderer
  OnePass,  ///< frustum / back-patch stages, the kernel before one pass
  TwoPass,  ///< occlusion: frame::CullFrame
};
const char* toString(FrameKind kind);

/// \brief What a MeshSession draws and how.
struct MeshSessionOptions {
  /// Names the mesh in the plan (its key) and in printed lines.
  std::string name = "mesh";
  std::string view = "view";
  /// Render options (tessellation, back-face culling), the cull settings (the mesh's
  /// back-patch validity, displacement map and uvCorners, the fixed stages without a
  /// planner), Hi-Z and pass options. With a planner the stages, passes and pyramid are the
  /// plan's (plan::applyPlan).
  frame::CullFrameOptions frame;
  /// Something else can hide the mesh (the occluders given, other meshes): offers
  /// occlusion to the plan.
  bool occluders = false;
  /// The cage moves every frame (a deforming mesh, frame::DynamicPatchMesh): the plan
  /// charges the point update and bounds pass and offers only methods with a bounds pass.
  bool deforming = false;
  /// A deforming mesh: the per-patch cull data of a back-patch method that its GPU bounds
  /// pass recomputes (DynamicPatchMesh::cullData); null or unset: built on the host.
  std::function<const vulkan::Buffer*(const std::string& method)> cullData;
  /// Kept configurations (cull passes and frames with their status), at least 1.
  size_t cachedConfigurations = 6;
};

/// \brief One frame of a session, in one layout whatever drew it.
struct SessionFrame {
  uint32_t index = 0;
  FrameKind kind = FrameKind::Plain;
  /// Every kind: patchesTotal, survivors, culled* (0 where no stage ran), frameMs (wall),
  /// pass1 statistics (the whole frame for Plain and OnePass); TwoPass: everything.
  frame::CullFrameStats stats;
  /// Plain and OnePass: the renderer's figures (draw calls, GPU time of the pass).
  frame::FrameStats onePass;
  /// With a planner: this frame's plan, and whether its stages differ from the last frame's.
  std::optional<plan::Plan> plan;
  bool planChanged = false;
  /// Counting-only passes run after the frame (Plan::countOnly) and their wall time,
  /// construction included (not in stats.frameMs).
  uint32_t countingPasses = 0;
  double countingMs = 0.0;
  /// TES and fragment invocations over both passes.
  uint64_t tesInvocations() const {
    return stats.pass1.tessEvaluationInvocations + stats.pass2.tessEvaluationInvocations;
  }
  uint64_t fragmentInvocations() const {
    return stats.pass1.fragmentShaderInvocations + stats.pass2.fragmentShaderInvocations;
  }
};

/// \brief The run so far (the end-of-run summary of `render`, `view` and bench-plan).
struct SessionSummary {
  uint32_t frames = 0;
  double meanMs = 0.0, medianMs = 0.0;  ///< wall time per frame
  uint64_t patches = 0;                 ///< patches of all frames
  uint64_t drawn = 0;                   ///< ... drawn
  uint64_t tesInvocations = 0;          ///< TES invocations of all frames
  /// Estimated TES invocations the culled patches would have run: each frame's culled
  /// patches times its drawn patches' mean (exact for uniform levels without transitions).
  uint64_t tesSaved = 0;
  uint32_t planChanges = 0;      ///< frames whose stages differ from the frame before
  double predictedMeanMs = 0.0;  ///< the plans' mean prediction (0 without a planner)
  size_t configurations = 0;     ///< passes and frames built
  /// \brief Two lines of text: times and work, then the plan's figures.
  std::string text() const;
};

/// \brief Adds frames up into a SessionSummary (MeshSession's, and the scene form's per view).
class SummaryAccumulator {
 public:
  /// \brief One frame: its figures and, with a plan, its predicted time (without point
  /// update) and whether its stages changed from the frame before.
  void add(const frame::CullFrameStats& stats, std::optional<double> predictedMs = std::nullopt,
           bool planChanged = false);
  void setConfigurations(size_t built) { summary_.configurations = built; }
  /// \brief The figures so far, the median taken now (not on every frame).
  SessionSummary summary() const;

 private:
  SessionSummary summary_;
  std::vector<double> frameMs_;  // the last frames' times (at most 8,192), for the median
  double predictedSum_ = 0.0;
  uint32_t planned_ = 0;
};

/// \brief The session. Everything passed in must outlive it.
class MeshSession {
 public:
  /// \brief A session drawing `host` (uploaded as `gpu`) into `target` with `occluders`
  /// drawn first. Without `planner`: the fixed stages of options.frame.cull, their pass or
  /// frame built now (unknown methods throw here, before any frame).
  MeshSession(vulkan::Context& context, frame::Renderer& renderer, frame::RenderTarget& target,
              frame::GpuPatchSet& gpu, const PatchSet& host,
              std::span<const frame::GpuTriangleMesh* const> occluders, MeshSessionOptions options,
              plan::Planner* planner = nullptr);
  ~MeshSession();
  MeshSession(const MeshSession&) = delete;
  MeshSession& operator=(const MeshSession&) = delete;

  /// \brief Draws the next frame from `camera` (whose size must be the target's).
  SessionFrame render(const frame::Camera& camera);

  /// \brief The plan's input for `camera` (the mesh, its validity, level, occluders).
  plan::PlanInput planInput(const frame::Camera& camera) const;
  /// \brief The two-pass frame the last frame drew with (null when it was not TwoPass).
  frame::CullFrame* cullFrame() { return last_ ? last_->frame.get() : nullptr; }
  /// \brief The cull pass of the last frame (its frame's, for TwoPass; null for Plain).
  const frame::CullPass* cullPass() const;
  /// \brief Configurations built so far (at most options.cachedConfigurations kept).
  size_t configurationsBuilt() const { return built_; }
  size_t configurationsKept() const { return cache_.size(); }
  SessionSummary summary() const { return summary_.summary(); }
  const MeshSessionOptions& options() const { return options_; }

 private:
  struct Configuration {
    std::string key;
    frame::CullFrameOptions options;
    std::unique_ptr<frame::CullFrame> frame;  // with occlusion
    std::unique_ptr<frame::CullPass> pass;    // without
  };
  Configuration& configuration(const std::string& key, const frame::CullFrameOptions& o);
  // The back-patch method's cull data the options' functor lends (null: the pass's own), and
  // a one-pass CullPass of `cull` with it.
  const vulkan::Buffer* cullData(const frame::CullSettings& cull) const;
  std::unique_ptr<frame::CullPass> makePass(const frame::CullSettings& cull) const;
  SessionFrame draw(Configuration* c, const frame::Camera& camera,
                    const frame::CullFrameOptions& o);
  // Plan::countOnly: each variant's cull pass run once without drawing, its back-patch culls
  // given to the planner.
  void count(const plan::Plan& p, const frame::Camera& camera, SessionFrame& f);

  vulkan::Context& context_;
  frame::Renderer& renderer_;
  frame::RenderTarget& target_;
  frame::GpuPatchSet& gpu_;
  const PatchSet& host_;
  std::vector<const frame::GpuTriangleMesh*> occluders_;
  MeshSessionOptions options_;
  plan::Planner* planner_;
  bool selfOccluding_ = true;
  frame::Bounds objectBounds_;
  std::list<Configuration> cache_;  // most recently used first
  Configuration* last_ = nullptr;
  size_t built_ = 0;
  uint32_t next_ = 0;
  std::optional<plan::StageChoice> lastStages_;
  SummaryAccumulator summary_;
};

}  // namespace osd_cull::session
