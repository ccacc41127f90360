#pragma once
/// \file cull_pass.h
/// \brief One cull dispatch over all patches of a GpuPatchSet (shaders/cull/cull_main.glsl):
/// the enabled stages cheapest first (frustum → back-patch method → occlusion), a result
/// code per patch (shaders/shared/cull_layout.h, bound/cull_reference.h reads it), a compact
/// draw list of the survivors and indirect draw commands over it.
///
/// Typical frame:
///   pass.record(cmd, camera, options.tessellation);      // before the render pass
///   renderer.beginPass(cmd, target, options);
///   pass.recordDraws(cmd, renderer, camera, options);     // survivors only
///   renderer.endPass(cmd);
/// or renderCulled() for all of that in one submission.
///
/// Every GPU cull is a cull of the double-precision reference (bound::referenceCull with
/// referenceTests() and cones()): fp32 decisions round toward "visible"
/// (docs/algorithms/cull-kernel.md).

#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/bound/cone_of_normals.h"
#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/bound/patch_clusters.h"
#include "osd_cull/frame/cull/cull_methods.h"
#include "osd_cull/frame/draw/renderer.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/handle.h"

#include <osd_cull/shared/cull_layout.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace osd_cull::frame {

/// \brief Which stages a pass runs.
struct CullSettings {
  bool frustum = true;
  std::string backPatch;  ///< a back-patch method name ("tcone", ...); empty: none
  std::string occlusion;  ///< an occlusion method name; empty: none
  /// Whether back-patch culling is valid on this mesh (bound::backPatchValidity). When it
  /// is not, the back-patch stage is left out and backPatchNote() gives the reason. The
  /// default is off: a caller must say that the mesh is a closed, outward-oriented solid.
  bound::BackPatchValidity backPatchValidity{false, "mesh validity not given"};
  /// Back-patch culls must be conservative for the triangles the tessellator draws, not only
  /// for the surface (bound/drawn_triangles.h): no chord triangle of a culled patch may face
  /// the eye. On by default; off gives the surface-exact tests the papers measure, which can
  /// lose single silhouette pixels (docs/algorithms/drawn-triangles.md).
  bool drawnTriangles = true;
  /// With drawnTriangles and uniform tessellation: a patch the worst-case bound keeps is
  /// still culled when every triangle the tessellator can draw for it faces away, each
  /// tested in the kernel from the control points (bound/drawn_triangle_set.h; the
  /// tightened test of docs/algorithms/drawn-triangles.md). No per-patch data is added, so
  /// it serves deforming meshes too. Off by default: it costs kernel time (see
  /// docs/results/accuracy-vs-time.md).
  bool drawnEnumerate = false;
  /// A displaced mesh: its map and PatchExtraction::uvCorners (both borrowed; they must
  /// outlive the pass). Then the frustum and occlusion stages test the displaced bound
  /// `displacedKernel` (an occlusion method that is a displaced kernel, e.g. "con-caf",
  /// chooses its own), and back-patch culling is off (backPatchNote() says why).
  const bound::DisplacementMap* displacementMap = nullptr;
  std::span<const glm::dvec2> uvCorners;
  CullMethod::Displaced displacedKernel;
  /// Instances of the patch set culled by the pass's one dispatch (issue 10: "many
  /// instances of one patch set share the control points and are culled in the same
  /// dispatch"), each with its own camera (view · model), results, draw list and counters.
  uint32_t instanceCount = 1;
  /// The control points stay as the host PatchSet has them for the pass's lifetime (no
  /// GpuPatchSet::updatePoints, readPointsFrom or GPU evaluator writing them). The pass then
  /// builds each patch's box once (patchBoxes()) and the kernel's frustum stage and the
  /// cones' drawn-triangle bound read 6 floats per patch instead of 16-20 control points,
  /// the larger part of the frustum kernel's cost on lavapipe (issue 24,
  /// docs/results/cull-kernel-floor.md). Culls stay culls of the reference (the box holds
  /// the points). Used only without an occlusion stage (which needs the points' NDC box)
  /// and on undisplaced meshes; off by default, since a pass cannot see points change.
  bool staticPoints = false;
  /// Clustered, hierarchical culling (bound/patch_clusters.h, docs/algorithms/clusters.md):
  /// a dispatch over clusters of patches first culls clusters outside the frustum (and,
  /// without drawnTriangles, back-facing ones) whole and accepts those inside and
  /// front-facing; the per-patch kernel then runs only on the patches of the undecided
  /// clusters (an indirect dispatch). Needs staticPoints (the cluster boxes and cones are
  /// built once), one instance, an undisplaced mesh, no occlusion stage and the tcone or
  /// ncone back-patch method (or none). Off by default.
  bool clusters = false;
  bound::ClusterCostModel clusterModel;  ///< the cluster sizes' cost model
};

/// \brief What the cluster dispatch of the last completed pass decided (CullSettings::clusters).
struct ClusterCounts {
  uint32_t clusters = 0;             ///< cluster tests
  uint32_t culled = 0;               ///< clusters culled whole
  uint32_t accepted = 0;             ///< clusters drawn without per-patch tests
  uint32_t undecided = 0;            ///< clusters whose patches were tested one by one
  uint32_t perPatchInvocations = 0;  ///< patches the per-patch kernel tested
};

struct CullPipelines;

/// \brief Survivor and draw counts of the last pass.
struct CullCounts {
  uint32_t survivorsBezier = 0;
  uint32_t survivorsGregory = 0;
  uint32_t drawsBezier = 0;  ///< indirect draw commands written
  uint32_t drawsGregory = 0;
  uint32_t survivors() const { return survivorsBezier + survivorsGregory; }
};

/// \brief Patches per indirect draw so that no lavapipe batch overflows (draw_chunks.h) with
/// `controlPoints` points per patch, for the largest vertex count `tessellation` can produce
/// (uniform: level 2N at transition edges, adaptive: maxLevel): at least 1, at most `count`.
uint32_t indirectDrawChunk(const TessellationOptions& tessellation, uint32_t controlPoints,
                           uint32_t count);

/// \brief The box of each patch's control points as the kernel reads it with
/// CullSettings::staticPoints (shaders/shared/cull_layout.h kCullBindingBoxes): float,
/// structure of arrays (min x of every patch, then min y, ..., max z), each bound rounded
/// outward, so that every box holds its patch's points exactly; NaN for a patch with a
/// non-finite point (kept by the kernel).
std::vector<float> packPatchBoxes(const PatchSet& patches);

/// \brief The pipelines, per-mesh data (cones) and output buffers of one cull
/// configuration for one patch set. The patch set must outlive the pass.
class CullPass {
 public:
  /// \brief The parts of a drawn-triangle kernel and where it takes the tessellation levels
  /// (defined in cull_pass.cpp; each part and source is a kernel of its own).
  enum class KernelPart;
  enum class LevelSource : uint32_t;

  /// \brief Builds the kernel variant for `settings` and uploads the per-mesh data (cones
  /// of the back-patch method, built on the host in double, rounded toward "visible").
  /// \throws osd_cull::Error for unknown method names, a method in the wrong stage, or a
  /// buffer, dispatch or draw count beyond a device limit (named; before anything exists).
  CullPass(vulkan::Context& context, GpuPatchSet& gpu, const PatchSet& host,
           const CullSettings& settings);
  /// \brief The same, reading the per-patch cull data from `cullData` (kConeVec4s vec4 per
  /// patch, e.g. BoundsPass::cullData() of the same method, recomputed on the GPU when the
  /// points move) instead of building cones on the host. `cullData` is borrowed and must
  /// outlive the pass; cones() is then empty (the reference builds cones from the frame's
  /// points: bound::buildPatchCones). A displaced mesh (settings.displacementMap) reads its
  /// displaced data from `cullData` the same way (DynamicPatchMesh::displacedCullData() of
  /// the kernel's extension); displacedPatches() is then empty.
  CullPass(vulkan::Context& context, GpuPatchSet& gpu, const PatchSet& host,
           const CullSettings& settings, const vulkan::Buffer& cullData);
  ~CullPass();
  CullPass(const CullPass&) = delete;
  CullPass& operator=(const CullPass&) = delete;

  const CullSettings& settings() const { return settings_; }
  /// \brief The methods the kernel runs, in stage order.
  const std::vector<const CullMethod*>& stages() const { return stages_; }
  /// \brief Whether the back-patch stage runs; backPatchNote() says why not.
  bool backPatchEnabled() const;
  const std::string& backPatchNote() const { return backPatchNote_; }
  /// \brief Whether the frustum and occlusion stages test a displaced bound, which one, and
  /// its per-patch data (Dmin/Dmax and cones, double, as uploaded before rounding; empty
  /// with external cull data: the bounds pass's, BoundsPass::readDisplaced()).
  bool displaced() const { return settings_.displacementMap != nullptr; }
  const CullMethod::Displaced& displacedKernel() const { return displacedKernel_; }
  std::span<const bound::DisplacedPatch> displacedPatches() const { return displaced_; }
  /// \brief Whether the kernel reads the precomputed boxes (CullSettings::staticPoints on an
  /// undisplaced mesh without an occlusion stage).
  bool patchBoxes() const;
  /// \brief Whether record() with `tessellation` runs the kernel without the listed-triangle
  /// test: drawn-triangle kernels without drawnEnumerate, under uniform levels at which no
  /// patch can be listed (every outer level above bound::kDrawnListLowLevel), so the verdicts
  /// are the same. On lavapipe the listing's code costs every invocation even when no patch
  /// reaches it: 4x the NCONE kernel at uniform level 4 (docs/results/cull-kernel-floor.md).
  bool leanKernelApplies(const TessellationOptions& tessellation) const;
  /// \brief Whether the pass tests clusters first (CullSettings::clusters), its clusters,
  /// the tests the cluster kernel runs (bound::testCluster is its reference), and the
  /// counts of the last completed pass.
  bool clustersEnabled() const { return settings_.clusters; }
  const bound::PatchClusters& clusters() const { return clusters_; }
  bound::ClusterTests clusterTests() const;
  ClusterCounts clusterCounts() const;
  /// \brief Host copies (double) of the uploaded cones, empty when none are used.
  std::span<const bound::ConeOfNormals> cones() const { return cones_; }
  /// \brief Whether back-patch culls respect the drawn triangles (CullSettings::
  /// drawnTriangles with a back-patch stage); the reference then needs the view's
  /// drawnTriangleShapes() in CullTests::drawnShapes.
  bool drawnTriangles() const { return settings_.drawnTriangles && backPatchEnabled(); }
  /// \brief The CPU reference of this configuration (bound::referenceCull), without the
  /// occlusion stage (and without drawnShapes, which depend on the view).
  bound::CullTests referenceTests() const;
  /// \brief The CPU reference of this configuration for one view drawn with `tessellation`:
  /// referenceTests() with drawnShapes pointing into `shapes` when drawnTriangles().
  bound::CullTests referenceTests(const Camera& camera, const TessellationOptions& tessellation,
                                  std::vector<bound::TriangleShape>& shapes) const;

  /// \brief Records the pass: counter reset, cull dispatch, draw-command dispatch, and
  /// barriers that make results, draw list and commands visible to the host, to indirect
  /// draws and to the patch draw shaders. `tessellation` fixes the draw chunking of the
  /// commands (recordDraws() must use the same). `stageSet` is the occlusion stage's
  /// descriptor set (set 1), required when one is enabled.
  void record(VkCommandBuffer cmd, const Camera& camera, const TessellationOptions& tessellation,
              VkDescriptorSet stageSet = VK_NULL_HANDLE);
  /// \brief The same for every instance at once: `cameras[i]` is instance i's camera in the
  /// patch set's object space (frame::instanceCamera(view camera, model i)), all with the
  /// view's viewport. One cull dispatch over (instance, patch), then one draw-command
  /// dispatch with a row per instance.
  /// \throws osd_cull::Error when cameras.size() differs from instanceCount().
  void record(VkCommandBuffer cmd, std::span<const Camera> cameras,
              const TessellationOptions& tessellation, VkDescriptorSet stageSet = VK_NULL_HANDLE);
  /// \brief Whether this pass's back-patch test reads exact adaptive levels under
  /// `tessellation` (drawnTriangles() of an undisplaced set, adaptive levels): record()
  /// then runs the levels pass (TessLevelsPass) into slot i of GpuPatchSet::tessLevels() for
  /// instance i, and every draw of the survivors must read those levels
  /// (PatchDraw::tessLevelSlot = i; recordDraws() does): a draw computing its own levels may
  /// differ by one level from what the test checked (docs/algorithms/drawn-triangles.md,
  /// "Exact adaptive levels").
  bool usesExactLevels(const TessellationOptions& tessellation) const;
  /// \brief Records the levels pass for these cameras now (e.g. before a frame's first
  /// pass, whose draws read them too); the next record() then does not record it again.
  /// Nothing when !usesExactLevels(tessellation).
  void recordTessLevels(VkCommandBuffer cmd, std::span<const Camera> cameras,
                        const TessellationOptions& tessellation);
  /// \brief The caller recorded the levels of this frame's cameras into tessLevelSlots()
  /// itself (Renderer::recordTessLevels, before its first pass): the next record() reads
  /// them and does not record them again.
  void useRecordedTessLevels() { levelsRecorded_ = true; }
  /// \brief The slot of GpuPatchSet::tessLevels() each instance reads (default: instance i
  /// slot i), for callers whose passes share a patch set (CullFrame).
  /// \throws osd_cull::Error for a wrong count or a slot the set does not have.
  void setTessLevelSlots(std::vector<uint32_t> slots);
  const std::vector<uint32_t>& tessLevelSlots() const { return levelSlots_; }
  /// \brief record() in its own submission; waits and returns the wall time in ms
  /// (timestamps are not trusted for compute after graphics on lavapipe, PLATFORM.md).
  double run(const Camera& camera, const TessellationOptions& tessellation = {},
             VkDescriptorSet stageSet = VK_NULL_HANDLE);

  /// \brief Result codes of the last completed pass, one per patch of instance `instance`
  /// (host-mapped memory).
  std::span<const uint32_t> results(uint32_t instance = 0) const;
  /// \brief Counts of the last completed pass for instance `instance`.
  CullCounts counts(uint32_t instance = 0) const;
  uint32_t instanceCount() const { return settings_.instanceCount; }
  /// \brief Cull dispatches recorded since construction (one per record()).
  uint64_t dispatchCount() const { return dispatches_; }
  /// \brief The survivors of the last completed pass: Bézier then Gregory, each in the
  /// (unspecified) order the kernel appended them.
  std::vector<uint32_t> survivors(vulkan::Context& context) const;

  /// \brief Records indirect draws of the survivors (inside a render pass, after record()
  /// in the same or an earlier submission). Returns the maximum number of draw commands.
  /// \throws osd_cull::Error when `options.tessellation` needs another draw chunking than
  /// the commands were written for, or for a pass of several instances (CullFrame draws
  /// those from their visibility status).
  uint32_t recordDraws(VkCommandBuffer cmd, Renderer& renderer, const Camera& camera,
                       const RenderOptions& options, uint32_t itemBase = 0);

  /// \brief The result codes as a buffer (one uint per patch and instance, instance i from
  /// uint i * patchCount), e.g. for a pass that reads them on the GPU after record() (the
  /// temporal visibility update of CullFrame).
  const vulkan::Buffer& resultsBuffer() const { return results_; }
  const vulkan::Buffer& drawList() const { return drawList_; }
  const vulkan::Buffer& commands() const { return commands_; }
  const vulkan::Buffer& counters() const { return counters_; }

 private:
  CullPass(vulkan::Context& context, GpuPatchSet& gpu, const PatchSet& host,
           const CullSettings& settings, const vulkan::Buffer* cullData);
  void buildPipelines(vulkan::Context& context);
  /// The composed kernel of one part and level source (cull_pass.cpp composeKernel).
  std::string kernelText(KernelPart part, LevelSource levels) const;
  /// The kernels a record with these levels runs: the cull kernel and, where it defers
  /// patches to the listed-triangle passes, the pass of each patch type the set has (else
  /// VK_NULL_HANDLE).
  struct Kernels {
    VkPipeline cull = VK_NULL_HANDLE;
    VkPipeline listed = VK_NULL_HANDLE;         ///< Bezier candidates
    VkPipeline listedGregory = VK_NULL_HANDLE;  ///< Gregory candidates
  };
  Kernels kernelsFor(const TessellationOptions& tessellation) const;
  void checkLimits(uint32_t patchCount) const;
  void uploadHostCones(vulkan::Context& context);
  void buildClusters(vulkan::Context& context);
  void recordClusters(VkCommandBuffer cmd);
  shader::CullConstants constants(const Camera& camera,
                                  const TessellationOptions& tessellation) const;
  shader::CullInstance instanceValues(const Camera& camera) const;

  vulkan::Context& context_;
  GpuPatchSet& gpu_;
  const PatchSet& host_;
  CullSettings settings_;
  std::vector<const CullMethod*> stages_;
  std::string backPatchNote_;
  uint32_t lanes_ = 1;
  std::vector<bound::ConeOfNormals> cones_;
  std::vector<bound::DisplacedPatch> displaced_;
  CullMethod::Displaced displacedKernel_;
  vulkan::Buffer displacedView_;  // DisplacedView per instance
  vulkan::Buffer instances_;      // header uvec4, then CullInstance per instance
  uint64_t dispatches_ = 0;

  vulkan::Buffer boxes_;                            // shared/cull_layout.h boxes[] (or 1 float)
  vulkan::Buffer conesBuffer_;                      // host-built cull data (unused if external)
  const vulkan::Buffer* cullData_ = &conesBuffer_;  // what the kernel reads
  vulkan::Buffer table_;
  vulkan::Buffer results_;
  vulkan::Buffer drawList_;
  vulkan::Buffer counters_;
  vulkan::Buffer deferred_;  // shared/cull_layout.h deferred[]: the listed-triangle candidates
  vulkan::Buffer commands_;
  bound::PatchClusters clusters_;  // empty without CullSettings::clusters
  vulkan::Buffer clusterWork_;     // shared/cluster_layout.h (a header only without clusters)
  vulkan::Buffer clusterData_;
  vulkan::Buffer clusterMembers_;
  std::shared_ptr<const CullPipelines> pipelines_;  // shared by passes with the same kernel
  std::unique_ptr<vulkan::DescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkDescriptorSet drawSet_ = VK_NULL_HANDLE;    // gpu_'s set with drawList_, made on first draw
  std::unique_ptr<TessLevelsPass> tessLevels_;  // made on first use
  VkBuffer boundTessLevels_ = VK_NULL_HANDLE;   // the tessLevels() set_ holds
  bool exactLevels_ = false;                    // of the last record()
  bool levelsRecorded_ = false;                 // recordTessLevels() since the last record()
  std::vector<uint32_t> levelSlots_;            // per instance
  uint32_t chunkBezier_ = 1;                    // of the last record()
  uint32_t chunkGregory_ = 1;
};

/// \brief One frame with culling, in one submission: the cull pass, then the occluders and
/// the surviving patches drawn into `target`. FrameStats::patchesDrawn is the survivor
/// count; the rest as Renderer::render. `stageSet` as in CullPass::record.
FrameStats renderCulled(Renderer& renderer, RenderTarget& target, const Camera& camera,
                        CullPass& pass, std::span<const GpuTriangleMesh* const> occluders,
                        const RenderOptions& options, VkDescriptorSet stageSet = VK_NULL_HANDLE);

}  // namespace osd_cull::frame
