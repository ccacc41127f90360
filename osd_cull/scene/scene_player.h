#pragma once
/// \file scene_player.h
/// \brief Plays a LoadedScene frame by frame: animates the cages, places the instances and
/// renders every view with its own two-pass CullFrame (Niessner & Loop §3) over the shared
/// meshes. Instances of one mesh share its control points (a deforming mesh: those with the
/// same time offset); each instance keeps its own visibility status per view and is culled
/// and drawn with view · model composed in double (frame::instanceCamera), so culling is as
/// precise far from the origin as at it.

#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/dynamic_patch_mesh.h"
#include "osd_cull/scene/loaded_scene.h"

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace osd_cull::scene {

/// \brief What one view did in one frame.
struct ViewFrame {
  std::string view;
  frame::Camera camera;
  frame::CullFrameStats stats;
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

/// \brief A culled frame's item image against the same frame drawn without culling.
struct UnculledComparison {
  uint64_t pixels = 0;         ///< of the image
  uint64_t covered = 0;        ///< covered by a patch or occluder in the unculled draw
  uint64_t lost = 0;           ///< covered unculled, background culled: must be 0
  uint64_t differing = 0;      ///< another item (depth ties between neighbours), or lost
  frame::FrameStats unculled;  ///< the unculled draw
};

/// \brief The player. The scene and the context must outlive it.
class ScenePlayer {
 public:
  /// \brief Uploads the meshes and occluders, makes a render target and a CullFrame per
  /// view with `options` (each mesh's back-patch validity replaces options.cull's). A
  /// deforming mesh moves its control points through a frame::DynamicPatchMesh on
  /// `pointUpdate`'s path and, with tcone or ncone, is back-patch culled with the cones the
  /// GPU bounds pass recomputes on every frame it moves; the tangent plane's drawn-triangle
  /// data is built on the host once, so that method stays off for it.
  ScenePlayer(vulkan::Context& context, LoadedScene& scene, const frame::CullFrameOptions& options,
              frame::PointUpdatePath pointUpdate = frame::PointUpdatePath::Cpu);
  ~ScenePlayer();
  ScenePlayer(const ScenePlayer&) = delete;
  ScenePlayer& operator=(const ScenePlayer&) = delete;

  /// \brief Sets the scene to frame `frame` (animations, instance matrices, cameras)
  /// without rendering.
  void seek(uint32_t frame);
  /// \brief seek(frame), then renders every view; one entry per view.
  std::vector<ViewFrame> render(uint32_t frame);
  /// \brief The current frame of view `view` drawn without any culling into `target`, with
  /// the same tessellation, back-face culling and image size (the like-for-like baseline).
  frame::FrameStats renderUnculled(size_t view, frame::RenderTarget& target);
  /// \brief renderUnculled(view, scratch) (scratch: the view's image size), then compares
  /// the item images of the view's last culled frame and that draw, pixel by pixel.
  /// \throws osd_cull::Error when `scratch`'s size differs from the view's.
  UnculledComparison compareWithUnculled(size_t view, frame::RenderTarget& scratch);

  size_t viewCount() const { return views_.size(); }
  frame::RenderTarget& target(size_t view) { return *views_.at(view).target; }
  frame::CullFrame& cullFrame(size_t view) { return *views_.at(view).frame; }
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
    std::unique_ptr<frame::CullFrame> frame;
    frame::Camera camera;
  };

  uint32_t users(const Points& points) const;  // instances drawing `points`

  vulkan::Context& context_;
  LoadedScene& scene_;
  std::unique_ptr<frame::Renderer> renderer_;
  std::vector<std::unique_ptr<Points>> points_;
  std::vector<Instance> instances_;
  std::vector<frame::GpuTriangleMesh> occluderMeshes_;
  std::vector<const frame::GpuTriangleMesh*> occluderPtrs_;
  std::vector<View> views_;
  frame::Bounds bounds_;
  frame::CullFrameOptions options_;
};

}  // namespace osd_cull::scene
