#pragma once
/// \file scene_player.h
/// \brief Plays a LoadedScene frame by frame: animates the cages, places the instances and
/// renders every view with its own two-pass CullFrame (Niessner & Loop §3) over the shared
/// meshes. Instances of one mesh share its control points (a deforming mesh: those with the
/// same time offset); each instance keeps its own visibility status per view and is culled
/// and drawn with view · model composed in double (frame::instanceCamera), so culling is as
/// precise far from the origin as at it.
///
/// With a planner (setPlanner(), docs/algorithms/plan.md "Scenes") every (view, instance)
/// gets its plan every frame and the plan is applied: the instance's cull stages (instances
/// with the same stages share a cull dispatch; a view's CullFrame is built once per set of
/// choices and kept for reuse), passes and Hi-Z resolution, its displaced kernel, and a view
/// where no instance culls is drawn by the plain renderer. The point update follows the
/// cage: a static mesh is never re-evaluated and a cage that did not move makes no point
/// update and no bounds dispatch. Each frame's per-instance culled counts and the view's
/// frame time are fed back (Planner::observe), so the rates are learned as the scene plays.

#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/dynamic_patch_mesh.h"
#include "osd_cull/frame/verify/item_comparison.h"
#include "osd_cull/plan/planner.h"
#include "osd_cull/scene/loaded_scene.h"

#include <list>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace osd_cull::session {

using scene::InstanceDescription;
using scene::LoadedScene;
using scene::SceneDescription;
using scene::SceneMesh;
using scene::ViewDescription;

/// \brief What one view did in one frame.
struct ViewFrame {
  std::string view;
  frame::Camera camera;
  frame::CullFrameStats stats;
  /// With a planner: each instance's plan of this frame, in instance order (else empty).
  std::vector<plan::Plan> plans;
  /// With a planner: false when no instance culls and the plain renderer drew the view.
  bool culled = true;
  /// Counting-only passes run after the frame (plan::Plan::countOnly of the static
  /// instances) and their wall time: outside `stats`, they draw nothing.
  uint32_t countingPasses = 0;
  double countingMs = 0.0;
};

/// \brief Work done for one set of shared control points (a mesh, or a deforming mesh at
/// one time offset) since the player was made: a static mesh never adds to it.
struct MeshWork {
  std::string mesh;
  bool deforms = false;
  uint32_t instances = 0;         ///< instances drawing these points
  uint64_t pointUpdates = 0;      ///< cage → control point recomputations
  uint64_t boundsDispatches = 0;  ///< bounds pass dispatches (frame/cull/bounds_pass.h)
};

/// \brief A view's culled frame against the same frame drawn without culling.
struct UnculledComparison {
  frame::ItemComparison items;  ///< of the item images
  frame::FrameStats unculled;   ///< the unculled draw
};

/// \brief The player. The scene and the context must outlive it.
class ScenePlayer {
 public:
  /// \brief Uploads the meshes and occluders, makes a render target and a CullFrame per
  /// view with `options` (each mesh's back-patch validity replaces options.cull's). A
  /// deforming mesh moves its control points through a frame::DynamicPatchMesh on
  /// `pointUpdate`'s path and is back-patch culled (tcone, ncone, tangent plane) with the
  /// cull data the GPU bounds pass recomputes on every frame it moves; a deforming
  /// displaced mesh with its displaced bound's cones, recomputed the same way.
  /// With `planner` (setPlanner()) no fixed-stage frame is built up front, so no bounds pass
  /// of the options' method runs unless a plan asks for it.
  ScenePlayer(vulkan::Context& context, LoadedScene& scene, const frame::CullFrameOptions& options,
              frame::PointUpdatePath pointUpdate = frame::PointUpdatePath::Cpu,
              plan::Planner* planner = nullptr);
  ~ScenePlayer();
  ScenePlayer(const ScenePlayer&) = delete;
  ScenePlayer& operator=(const ScenePlayer&) = delete;

  /// \brief Plans every (view, instance) each frame from now on (null: the fixed stages of
  /// the constructor's options again). The planner must outlive its use; its keys are
  /// plan::scenePlanKey(). The tessellation planned for is the options' uniform level, an
  /// adaptive one as the uniform level of the same work (plan::equivalentUniformLevel).
  void setPlanner(plan::Planner* planner);
  /// \brief Sets the scene to frame `frame` (animations, instance matrices, cameras)
  /// without rendering.
  void seek(uint32_t frame);
  /// \brief seek(frame), then renderCurrent(frame): every view; one entry per view.
  std::vector<ViewFrame> render(uint32_t frame);
  /// \brief Renders every view at the frame seek() set, with the cameras it set or
  /// setCamera() replaced; with a planner, planned as frame `planFrame` (increasing).
  std::vector<ViewFrame> renderCurrent(uint64_t planFrame);
  /// \brief Replaces view `view`'s camera until the next seek() (a viewer's own camera).
  /// \throws std::out_of_range for an unknown view.
  void setCamera(size_t view, const frame::Camera& camera);
  /// \brief The current frame of view `view` drawn without any culling into `target`, with
  /// the same tessellation, back-face culling and image size (the like-for-like baseline).
  frame::FrameStats renderUnculled(size_t view, frame::RenderTarget& target);
  /// \brief renderUnculled(view, scratch) (scratch: the view's image size), then compares
  /// the item images of the view's last culled frame and that draw, pixel by pixel.
  /// \throws osd_cull::Error when `scratch`'s size differs from the view's.
  UnculledComparison compareWithUnculled(size_t view, frame::RenderTarget& scratch);

  size_t viewCount() const { return views_.size(); }
  frame::RenderTarget& target(size_t view) { return *views_.at(view).target; }
  /// \brief The CullFrame view `view` rendered with last (with a planner: the one of the
  /// last frame's choices).
  /// \throws osd_cull::Error when a planned view has not been culled yet (drawn without
  /// culling so far).
  frame::CullFrame& cullFrame(size_t view);
  /// \brief CullFrames built for view `view` so far (with a planner: one per set of stage
  /// choices seen, each kept for reuse).
  size_t cullFrameCount(size_t view) const { return views_.at(view).frames.size(); }
  /// \brief The planned CullFrames built for `view` so far, those evicted included.
  size_t cullFramesBuilt(size_t view) const { return views_.at(view).built; }
  /// \brief How many planned CullFrames (sets of choices) a view keeps, least recently used
  /// evicted first (default 6; at least 1): memory stays flat however many sets of choices
  /// a restless plan visits (issue 18). A set met again after its eviction is rebuilt and
  /// starts with nothing visible, like any new one.
  void setCachedFrames(size_t frames);
  /// \brief The camera of view `view` at the current frame.
  const frame::Camera& camera(size_t view) const { return views_.at(view).camera; }
  std::span<const frame::GpuTriangleMesh* const> occluders() const { return occluderPtrs_; }
  frame::Renderer& renderer() { return *renderer_; }
  /// \brief Patches over all instances.
  uint32_t patchCount() const;
  size_t instanceCount() const { return instances_.size(); }
  /// \brief Instance `i`'s patches (object space, current pose) and model matrix.
  const PatchSet& patches(size_t i) const;
  const glm::dmat4& model(size_t i) const { return instances_.at(i).model; }
  /// \brief World bounds of every instance and occluder at the current frame.
  const frame::Bounds& bounds() const { return bounds_; }
  /// \brief Lines saying which meshes share points, deform, or skip back-patch culling.
  std::vector<std::string> describe() const;
  /// \brief Per set of shared control points, in the order describe() lists them.
  std::vector<MeshWork> work() const;
  /// \brief The device patch set instance `i` draws (with its displacement map bound when
  /// its mesh is displaced).
  const frame::GpuPatchSet& gpuPatches(size_t i) const;
  /// \brief The moving control points of instance `i` (cage input, GPU bounds passes), or
  /// nullptr when its mesh is static.
  frame::DynamicPatchMesh* dynamicMesh(size_t i);

 private:
  struct Points;
  struct Instance {
    size_t points = 0;  // index into points_
    glm::dmat4 model{1.0};
  };
  struct View {
    std::unique_ptr<frame::RenderTarget> target;
    // Keyed by the instances' stage choices ("" for the fixed options).
    std::map<std::string, std::unique_ptr<frame::CullFrame>> frames;
    std::list<std::string> recent;      // keys of the planned frames, most recent first
    size_t built = 0;                   // planned frames built, evicted ones included
    frame::CullFrame* frame = nullptr;  // the last one rendered
    frame::Camera camera;
  };

  uint32_t users(const Points& points) const;  // instances drawing `points`
  // Instance `i` as a CullMesh culled with `stages` (null: the options' stages) and, when
  // its mesh is displaced, the displaced bound `kernel` (null: the scene's), with the cull
  // data its (deforming, displaced) mesh needs for them.
  frame::CullMesh cullMesh(size_t i, const frame::CullStages* stages,
                           const frame::CullMethod::Displaced* kernel);
  // The view's CullFrame of these plans' choices, built on first use (`built` says so).
  frame::CullFrame& fixedFrame(size_t view);  // the options' stages, built on first use
  frame::CullFrame& plannedFrame(size_t view, const std::vector<plan::Plan>& plans, bool& built);
  ViewFrame renderPlanned(size_t view, uint64_t frameIndex);
  // Runs the plans' counting-only passes of `out` (Plan::countOnly) and feeds their
  // back-patch culls to the planner.
  void count(size_t view, ViewFrame& out);
  frame::FrameStats drawUnculled(size_t view, frame::RenderTarget& target);

  vulkan::Context& context_;
  LoadedScene& scene_;
  size_t cachedFrames_ = 6;
  std::unique_ptr<frame::Renderer> renderer_;
  std::vector<std::unique_ptr<Points>> points_;
  std::vector<Instance> instances_;
  std::vector<frame::GpuTriangleMesh> occluderMeshes_;
  std::vector<const frame::GpuTriangleMesh*> occluderPtrs_;
  std::vector<View> views_;
  frame::Bounds bounds_;
  frame::CullFrameOptions options_;
  std::optional<bound::BackPatchMethod> backPatch_;  // the options' cone method, if any
  plan::Planner* planner_ = nullptr;
  std::vector<bool> moved_;          // per Points: posed anew by the last seek()
  std::vector<bool> selfOccluding_;  // per instance (plan::meshMayHideItself), with a planner
};

}  // namespace osd_cull::session
