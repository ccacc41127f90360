#pragma once
/// \file cull_verification.h
/// \brief Checks cull passes view by view against every ground truth the project has, and
/// measures them (used by `osd-cull verify`, the cull tests and benchmarks):
/// - the double-precision CPU reference (bound::referenceCull): every GPU cull must be a
///   reference cull ("GPU culled set ⊆ CPU culled set");
/// - the visibility oracle (frame/visibility_oracle.h): a culled patch with pixels in the
///   unculled item buffer is a false cull;
/// - dense sampling in double (bound/sampling.h): a frustum-culled patch has no sample in the
///   clip volume, a back-patch-culled patch no front-facing sample;
/// - the image: drawing only the survivors leaves no pixel uncovered that the full draw
///   covers.
/// Each method runs alone (frustum alone, each back-patch method alone, the occlusion method
/// alone), so its rate is its own. An occlusion method ("hiz") tests against the Hi-Z pyramid
/// of the full draw's depth (what a static camera settles at, Niessner & Loop §3); its CPU
/// reference is bound::hizOcclusionTest on the same depth, read back.

#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/bound/displaced_bounds.h"
#include "osd_cull/bound/sampling.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/hiz/hiz_cull_stage.h"
#include "osd_cull/frame/hiz/hiz_pyramid.h"
#include "osd_cull/frame/verify/visibility_oracle.h"

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace osd_cull::frame {

/// \brief What to check per view.
struct VerifyOptions {
  TessellationOptions tessellation;  ///< of the oracle and image draws
  bool oracle = true;
  /// Compare with the CPU reference on every referenceStride-th view (0: never).
  uint32_t referenceStride = 1;
  /// Dense sampling grid (n x n segments per patch) for culled patches; 0: off.
  int samplingGrid = 0;
  /// Draw survivors and compare coverage with the full draw (needs oracle).
  bool imageCheck = false;
  /// Pyramid of the occlusion methods (half resolution, the paper's lookup by default).
  HiZOptions hiz;
  /// Back-patch methods respect the drawn triangles (CullSettings::drawnTriangles); false
  /// runs the surface-exact tests the papers measure.
  bool drawnTriangles = true;
  /// With drawnTriangles: the tightened test that lists the drawn triangles
  /// (CullSettings::drawnEnumerate).
  bool drawnEnumerate = false;
  /// The methods clustered culling serves (frustum, tcone, ncone) run with
  /// CullSettings::clusters (static points, host-built cull data), the others as always.
  bool clusters = false;
  /// Oracle and image draws cull back-facing triangles, as a renderer does on a closed,
  /// outward-oriented mesh. Default: on exactly when back-patch culling is valid for the
  /// mesh. Then a patch culled with the drawn-triangle bound has no triangle that is drawn
  /// at all, so it can own no pixel, even through a pinhole of the tessellated surface.
  std::optional<bool> cullBackFaces;
  /// A displaced mesh (CullSettings::displacementMap, uvCorners; borrowed): the oracle and
  /// image draws draw the displaced surface, every method tests displaced bounds, the
  /// displaced kernels (full-oobb ... con-caf) can run, back-patch methods are skipped, and
  /// the dense sampling check (undisplaced samples) is off.
  const bound::DisplacementMap* displacementMap = nullptr;
  std::span<const glm::dvec2> uvCorners;
  /// Per cone method (TCone, NCone): the cull data the GPU bounds pass computed for these
  /// points (DynamicPatchMesh::cullData; borrowed), read by that method's pass instead of
  /// cones built on the host, so the check covers what a deforming mesh is culled with.
  std::map<bound::BackPatchMethod, const vulkan::Buffer*> cullData;
  /// Per displaced extension (Full, ACoN, CoN): the displaced cull data the GPU bounds pass
  /// computed for these points (DynamicPatchMesh::displacedCullData, shared/cull_layout.h
  /// kConeVec4s vec4 per patch; borrowed), read by the displaced kernels of that extension
  /// instead of data built on the host, as a deforming displaced mesh is culled
  /// (ScenePlayer). Their double reference (displacedReferenceCull) then runs on that data
  /// read back and widened to double, with the exact Dmin/Dmax of the map.
  std::map<bound::DisplacedExtension, const vulkan::Buffer*> displacedCullData;
  /// Count crack pixels per view (frame::countCracks: two more draws, back faces culled
  /// and not): for displaced meshes, where UV seams open the surface.
  bool countCracks = false;
};

/// \brief Crack pixels over the views (VerifyOptions::countCracks).
struct CrackTotals {
  uint64_t views = 0;
  uint64_t pixels = 0;
  uint64_t viewsWithCracks = 0;
  uint64_t worstView = 0;  ///< the most crack pixels in one view
};

/// \brief Totals of one method over all views so far.
struct MethodTotals {
  std::string name;
  CullStage stage = CullStage::Frustum;
  uint64_t views = 0;
  uint64_t patchViews = 0;
  uint64_t culled = 0;
  uint64_t culledBezier = 0;
  uint64_t culledGregory = 0;
  /// Patch-views the surface test culls but the drawn-triangle bound keeps
  /// (BackPatchVerdict::DrawnTriangles).
  uint64_t keptForDrawnTriangles = 0;
  uint64_t bezierViews = 0;   ///< Bézier patch-views
  uint64_t gregoryViews = 0;  ///< Gregory patch-views
  /// CPU reference (on the views where it ran).
  uint64_t referenceViews = 0;
  uint64_t referencePatchViews = 0;
  uint64_t referenceCulled = 0;
  uint64_t agreements = 0;      ///< same culled/kept decision as the reference
  uint64_t notInReference = 0;  ///< GPU culled, reference kept: must be 0
  /// Oracle.
  uint64_t oracleViews = 0;
  uint64_t oraclePatchViews = 0;
  uint64_t oracleInvisible = 0;  ///< patch-views with zero pixels
  uint64_t falseCulls = 0;       ///< culled patch-views with pixels: must be 0
  uint64_t falseCullPixels = 0;  ///< their pixels
  /// The first false culls (view index, patch, pixels), at most 64, for diagnosis.
  struct FalseCull {
    uint64_t view = 0;
    uint32_t patch = 0;
    uint32_t pixels = 0;
  };
  std::vector<FalseCull> falseCullList;
  uint64_t culledOnOracleViews = 0;
  /// Sampling.
  uint64_t sampledCulls = 0;
  uint64_t samplingViolations = 0;  ///< culled with a visible sample: must be 0
  /// Image.
  uint64_t imageViews = 0;
  uint64_t pixelsLost = 0;     ///< covered unculled, background culled: must be 0
  uint64_t pixelsChanged = 0;  ///< covered by another patch (depth ties), for information
  std::vector<double> wallMs;  ///< cull submission wall time per view

  double cullRate() const { return patchViews ? double(culled) / double(patchViews) : 0.0; }
  double referenceCullRate() const;
  double referenceAgreement() const;
  double oracleInvisibleRate() const;
  /// Median wall time per patch in ns (submission of counter reset, cull and draw-command
  /// dispatches, and wait).
  double nsPerPatch(uint32_t patchCount) const;
};

/// \brief Runs the passes of a list of methods on one patch set, view after view.
class CullVerifier {
 public:
  /// \brief `methods` are registry names (cull_methods.h). Back-patch methods are skipped
  /// (see skipped()) when `validity` disallows back-patch culling.
  CullVerifier(vulkan::Context& context, const PatchSet& host,
               const std::vector<std::string>& methods, const bound::BackPatchValidity& validity,
               const VerifyOptions& options);
  ~CullVerifier();

  /// \brief Runs every method on `camera` and adds to the totals.
  void verifyView(const Camera& camera);

  const std::vector<MethodTotals>& totals() const { return totals_; }
  /// \brief Methods not run, with the reason.
  const std::vector<std::pair<std::string, std::string>>& skipped() const { return skipped_; }
  const PatchSet& patches() const { return host_; }
  /// \brief Whether the oracle and image draws cull back-facing triangles.
  bool cullBackFaces() const { return cullBackFaces_; }
  /// \brief Crack pixels so far (VerifyOptions::countCracks).
  const CrackTotals& cracks() const { return cracks_; }

 private:
  struct Method;
  struct ViewTruth;
  /// \brief The dense sampling check of one method's culls on one view.
  void checkSampling(Method& m, const Camera& camera, std::span<const uint32_t> results);
  /// \brief (Re)creates the target, and with occlusion methods its pyramid and Hi-Z stage,
  /// when the view's size changes.
  void prepareTarget(const Camera& camera, bool occlusion);
  /// \brief The full draw's ground truth for one view: the oracle's counts and items, the
  /// Hi-Z pyramid (built on the GPU, and in double on reference views).
  ViewTruth drawTruth(const Camera& camera, bool reference, bool occlusion);
  /// \brief Runs one method on the view and adds its culls and every check to its totals.
  void verifyMethod(Method& m, const Camera& camera, const ViewTruth& truth);
  /// \brief The CPU reference's cull codes of one method on the view, per patch.
  std::vector<uint32_t> referenceCodes(Method& m, const Camera& camera, const ViewTruth& truth);
  /// \brief Draws one method's survivors and counts the pixels lost and changed against the
  /// full draw.
  void checkImage(Method& m, const Camera& camera, const ViewTruth& truth);
  /// \brief Counts the view's crack pixels into cracks_ (draws over the target).
  void countViewCracks(const Camera& camera);

  vulkan::Context& context_;
  const PatchSet& host_;
  VerifyOptions options_;
  GpuPatchSet gpu_;
  Renderer renderer_;
  VisibilityOracle oracle_;
  std::unique_ptr<GpuDisplacement> displacement_;  // on gpu_, for displaced meshes
  std::unique_ptr<RenderTarget> target_;
  std::unique_ptr<HiZPyramid> pyramid_;  // over target_'s depth, with occlusion methods
  std::unique_ptr<HiZCullStage> hizStage_;
  std::vector<std::unique_ptr<Method>> methods_;
  std::vector<MethodTotals> totals_;
  std::vector<std::pair<std::string, std::string>> skipped_;
  std::vector<bound::SurfaceSamples> samples_;         // per patch, when sampling is on
  std::vector<bound::DisplacementRange> exactRanges_;  // with displacedCullData, built once
  uint64_t viewIndex_ = 0;
  bool cullBackFaces_ = false;  // of the oracle and image draws
  CrackTotals cracks_;
};

}  // namespace osd_cull::frame
