#include "osd_cull/frame/verify/cull_verification.h"

#include "osd_cull/frame/verify/crack_count.h"

#include "osd_cull/frame/cull/cull_pass_displaced.h"

#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/bound/occlusion.h"
#include "osd_cull/error.h"
#include "osd_cull/vk/transfer.h"

#include <osd_cull/shared/cull_layout.h>
#include <osd_cull/shared/draw_layout.h>

#include <algorithm>

namespace osd_cull::frame {

struct CullVerifier::Method {
  const CullMethod* method = nullptr;
  std::unique_ptr<CullPass> pass;
  MethodTotals* totals = nullptr;
  std::vector<bound::ConeOfNormals> referenceCones;  // with GPU cull data, built once
  const vulkan::Buffer* displacedData = nullptr;     // VerifyOptions::displacedCullData
};

double MethodTotals::referenceCullRate() const {
  return referencePatchViews ? double(referenceCulled) / double(referencePatchViews) : 0.0;
}

double MethodTotals::referenceAgreement() const {
  return referencePatchViews ? double(agreements) / double(referencePatchViews) : 0.0;
}

double MethodTotals::oracleInvisibleRate() const {
  return oraclePatchViews ? double(oracleInvisible) / double(oraclePatchViews) : 0.0;
}

double MethodTotals::nsPerPatch(uint32_t patchCount) const {
  if (wallMs.empty() || patchCount == 0) return 0.0;
  std::vector<double> sorted = wallMs;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  return sorted[sorted.size() / 2] * 1e6 / patchCount;
}

CullVerifier::CullVerifier(vulkan::Context& context, const PatchSet& host,
                           const std::vector<std::string>& methods,
                           const bound::BackPatchValidity& validity, const VerifyOptions& options)
    : context_(context),
      host_(host),
      options_(options),
      gpu_(context, host),
      renderer_(context),
      oracle_(context),
      cullBackFaces_(options.cullBackFaces.value_or(validity.enabled)) {
  if (options.displacementMap) {
    displacement_ = std::make_unique<GpuDisplacement>(context, *options.displacementMap,
                                                      options.uvCorners, host.patchCount());
    gpu_.setDisplacement(displacement_.get());
  }
  if (options.imageCheck && !options.oracle)
    throw Error("CullVerifier: the image check compares with the oracle's full draw; enable it");
  std::vector<const CullMethod*> run;
  for (const std::string& name : methods) {
    const CullMethod& m = cullMethod(name);
    if (m.stage == CullStage::Occlusion && !options.oracle) {
      skipped_.push_back({name,
                          "occlusion is tested against the depth of the oracle's draw; "
                          "enable the oracle"});
    } else if (m.stage == CullStage::BackPatch && options.displacementMap) {
      skipped_.push_back(
          {name, std::string("back-patch culling is off: ") + kDisplacedBackPatchNote});
    } else if (m.displaced && !options.displacementMap) {
      skipped_.push_back({name, "a displaced kernel; this mesh has no displacement map"});
    } else if (m.stage == CullStage::BackPatch && !validity.enabled) {
      skipped_.push_back({name, "back-patch culling is off for this mesh: " + validity.reason});
    } else {
      run.push_back(&m);
    }
  }
  totals_.resize(run.size());
  for (size_t i = 0; i < run.size(); ++i) {
    auto m = std::make_unique<Method>();
    m->method = run[i];
    CullSettings settings;
    settings.frustum = run[i]->stage == CullStage::Frustum;
    if (run[i]->stage == CullStage::BackPatch) settings.backPatch = run[i]->name;
    if (run[i]->stage == CullStage::Occlusion) settings.occlusion = run[i]->name;
    settings.backPatchValidity = validity;
    settings.drawnTriangles = options.drawnTriangles;
    settings.drawnEnumerate = options.drawnEnumerate;
    settings.displacementMap = options.displacementMap;
    settings.uvCorners = options.uvCorners;
    const auto data = options.cullData.find(run[i]->reference);
    settings.clusters =
        options.clusters && !options.displacementMap && data == options.cullData.end() &&
        (run[i]->stage == CullStage::Frustum || run[i]->name == "tcone" || run[i]->name == "ncone");
    settings.staticPoints = settings.clusters;
    if (run[i]->displaced) {
      const auto d = options.displacedCullData.find(run[i]->displaced->extension);
      if (d != options.displacedCullData.end()) m->displacedData = d->second;
    }
    m->pass = run[i]->stage == CullStage::BackPatch && data != options.cullData.end()
                  ? std::make_unique<CullPass>(context, gpu_, host, settings, *data->second)
              : m->displacedData
                  ? std::make_unique<CullPass>(context, gpu_, host, settings, *m->displacedData)
                  : std::make_unique<CullPass>(context, gpu_, host, settings);
    m->totals = &totals_[i];
    totals_[i].name = run[i]->name;
    totals_[i].stage = run[i]->stage;
    methods_.push_back(std::move(m));
  }
  if (options.samplingGrid > 0 && !options.displacementMap) {
    samples_.reserve(host.patchCount());
    for (uint32_t p = 0; p < host.patchCount(); ++p)
      samples_.push_back(bound::samplePatch(host.controlPoints(p), options.samplingGrid));
  }
}

CullVerifier::~CullVerifier() = default;

void CullVerifier::checkSampling(Method& m, const Camera& camera,
                                 std::span<const uint32_t> results) {
  const glm::dmat4 viewProj = camera.viewProjection();
  const bound::CullView view = bound::makeCullView(viewProj);
  for (uint32_t p = 0; p < results.size(); ++p) {
    const bound::CullCode code{results[p]};
    if (!code.culled()) continue;
    ++m.totals->sampledCulls;
    bool visible = false;
    if (code.stage() == shader::kStageFrustum)
      visible = bound::anyInsideClipVolume(samples_[p], viewProj);
    else if (code.stage() == shader::kStageBackPatch)
      visible = !view.eye || bound::anyFrontFacing(samples_[p], *view.eye);
    if (visible) ++m.totals->samplingViolations;
  }
}

/// \brief What one view gives every method to compare with: the oracle's counts and items
/// of the full draw, the double-precision Hi-Z pyramid of its depth, the view's planes.
struct CullVerifier::ViewTruth {
  bool reference = false;  ///< the CPU reference runs on this view (referenceStride)
  VisibilityCounts counts;
  std::vector<uint32_t> fullItems;  ///< the full draw's item buffer, with the image check
  bound::HiZPyramid hizReference;   ///< with occlusion methods on reference views
  bound::CullView view;
  RenderOptions drawOptions;  ///< of the image check's draws
};

namespace {

/// \brief Adds one view's culls (by patch type, and those the drawn-triangle bound kept) to
/// `t`.
void countCulls(MethodTotals& t, const PatchSet& host, std::span<const uint32_t> results) {
  const uint32_t n = host.patchCount();
  ++t.views;
  t.patchViews += n;
  t.bezierViews += host.bezierCount;
  t.gregoryViews += host.gregoryCount;
  for (uint32_t p = 0; p < n; ++p) {
    t.keptForDrawnTriangles +=
        bound::CullCode{results[p]}.backPatch() == shader::kVerdictDrawnTriangles;
    if (!bound::CullCode{results[p]}.culled()) continue;
    ++t.culled;
    ++(host.type(p) == PatchType::Bezier ? t.culledBezier : t.culledGregory);
  }
}

/// \brief Adds one view's comparison of the GPU's culls with the CPU reference's codes to `t`.
void compareWithReference(MethodTotals& t, std::span<const uint32_t> results,
                          std::span<const uint32_t> codes) {
  ++t.referenceViews;
  t.referencePatchViews += results.size();
  for (size_t p = 0; p < results.size(); ++p) {
    const bool gpuCulled = bound::CullCode{results[p]}.culled();
    const bool cpuCulled = bound::CullCode{codes[p]}.culled();
    t.referenceCulled += cpuCulled;
    t.agreements += gpuCulled == cpuCulled;
    t.notInReference += gpuCulled && !cpuCulled;
  }
}

/// \brief Adds one view's comparison of the GPU's culls with the oracle's pixel counts to
/// `t`: a culled patch with pixels is a false cull (the first 64 listed, with `view`).
void compareWithOracle(MethodTotals& t, std::span<const uint32_t> results,
                       const VisibilityCounts& counts, uint64_t view) {
  ++t.oracleViews;
  t.oraclePatchViews += results.size();
  for (uint32_t p = 0; p < results.size(); ++p) {
    const bool culled = bound::CullCode{results[p]}.culled();
    t.oracleInvisible += counts.pixels[p] == 0;
    t.culledOnOracleViews += culled;
    t.falseCulls += culled && counts.pixels[p] > 0;
    if (culled) t.falseCullPixels += counts.pixels[p];
    if (culled && counts.pixels[p] > 0 && t.falseCullList.size() < 64)
      t.falseCullList.push_back({view, p, counts.pixels[p]});
  }
}

}  // namespace

void CullVerifier::prepareTarget(const Camera& camera, bool occlusion) {
  if (target_ && target_->width() == camera.width && target_->height() == camera.height) return;
  hizStage_.reset();
  pyramid_.reset();
  target_ = std::make_unique<RenderTarget>(context_, camera.width, camera.height);
  if (occlusion) {
    pyramid_ = std::make_unique<HiZPyramid>(context_, target_->depth(), options_.hiz);
    hizStage_ = std::make_unique<HiZCullStage>(context_, *pyramid_);
  }
}

CullVerifier::ViewTruth CullVerifier::drawTruth(const Camera& camera, bool reference,
                                                bool occlusion) {
  ViewTruth truth;
  truth.reference = reference;
  if (options_.oracle) {
    truth.counts = oracle_.query(renderer_, *target_, camera, gpu_, &host_, {},
                                 options_.tessellation, 0, cullBackFaces_);
    if (options_.imageCheck) truth.fullItems = target_->readItems(context_);
  }
  // Occlusion: the pyramid of the full draw's depth (before the image checks draw over it),
  // and its double-precision twin for the reference.
  if (occlusion) {
    pyramid_->build(context_, RenderTarget::kDepthLayout);
    if (reference)
      truth.hizReference = bound::buildHiZPyramid(target_->readDepth(context_), camera.width,
                                                  camera.height, options_.hiz.fullResolution);
  }
  truth.view = bound::makeCullView(camera.viewProjection());
  truth.drawOptions.tessellation = options_.tessellation;
  truth.drawOptions.cullBackFaces = cullBackFaces_;
  return truth;
}

std::vector<uint32_t> CullVerifier::referenceCodes(Method& m, const Camera& camera,
                                                   const ViewTruth& truth) {
  const uint32_t n = host_.patchCount();
  const bool hiz = m.method->stage == CullStage::Occlusion;
  const bound::HiZPyramid* hizReference = hiz ? &truth.hizReference : nullptr;
  std::vector<uint32_t> codes;
  if (m.pass->displaced()) {
    if (m.displacedData) {
      // What the kernel read: the GPU bounds pass's cones, with the exact D range.
      std::vector<bound::DisplacedPatch> data =
          unpackDisplacedPatches(vulkan::readback<float>(context_, *m.displacedData), n);
      if (exactRanges_.empty())
        exactRanges_ =
            bound::displacementRanges(host_, options_.uvCorners, *options_.displacementMap);
      for (uint32_t p = 0; p < n; ++p) data[p].range = exactRanges_[p];
      codes =
          displacedReferenceCull(host_, *m.pass, data, camera, hizReference, options_.hiz.lookup);
    } else {
      codes = displacedReferenceCull(host_, *m.pass, camera, hizReference, options_.hiz.lookup);
    }
  } else if (hiz) {
    codes.resize(n, shader::kStageNone);
    for (uint32_t p = 0; p < n; ++p)
      if (bound::hizOcclusionTest(host_.controlPoints(p), truth.view.viewProj, truth.hizReference,
                                  options_.hiz.lookup)
              .culled)
        codes[p] = shader::kStageOcclusion;
  } else {
    std::vector<bound::TriangleShape> shapes;
    const bound::CullTests tests = m.pass->referenceTests(camera, options_.tessellation, shapes);
    // A pass reading GPU-computed cull data (VerifyOptions::cullData) keeps no host
    // cones: the reference builds them from the same points in double.
    if (m.pass->backPatchEnabled() && m.pass->cones().empty() && m.referenceCones.empty())
      m.referenceCones = bound::buildPatchCones(host_, tests.backPatch);
    codes = bound::referenceCull(host_, truth.view, tests,
                                 m.pass->cones().empty()
                                     ? std::span<const bound::ConeOfNormals>(m.referenceCones)
                                     : m.pass->cones());
  }
  return codes;
}

void CullVerifier::checkImage(Method& m, const Camera& camera, const ViewTruth& truth) {
  MethodTotals& t = *m.totals;
  const bool hiz = m.method->stage == CullStage::Occlusion;
  renderCulled(renderer_, *target_, camera, *m.pass, {}, truth.drawOptions,
               hiz ? hizStage_->set() : VK_NULL_HANDLE);
  const std::vector<uint32_t> items = target_->readItems(context_);
  ++t.imageViews;
  for (size_t i = 0; i < items.size(); ++i) {
    if (truth.fullItems[i] == shader::kItemBackground) continue;
    if (items[i] == shader::kItemBackground)
      ++t.pixelsLost;
    else if (items[i] != truth.fullItems[i])
      ++t.pixelsChanged;
  }
}

void CullVerifier::verifyMethod(Method& m, const Camera& camera, const ViewTruth& truth) {
  MethodTotals& t = *m.totals;
  const bool hiz = m.method->stage == CullStage::Occlusion;
  t.wallMs.push_back(
      m.pass->run(camera, options_.tessellation, hiz ? hizStage_->set() : VK_NULL_HANDLE));
  const std::vector<uint32_t> results(m.pass->results().begin(), m.pass->results().end());
  countCulls(t, host_, results);
  const auto perPatch = std::span<const uint32_t>(results).first(host_.patchCount());
  if (truth.reference) compareWithReference(t, perPatch, referenceCodes(m, camera, truth));
  if (options_.oracle) compareWithOracle(t, perPatch, truth.counts, viewIndex_ - 1);
  if (!samples_.empty()) checkSampling(m, camera, results);
  if (options_.imageCheck) checkImage(m, camera, truth);
}

void CullVerifier::countViewCracks(const Camera& camera) {
  RenderOptions crackOptions;
  crackOptions.tessellation = options_.tessellation;
  const PatchDraw draw{&gpu_, &host_, 0};
  const uint32_t pixels =
      countCracks(context_, renderer_, *target_, camera, draw, crackOptions, kSeamCrackWidth);
  ++cracks_.views;
  cracks_.pixels += pixels;
  cracks_.viewsWithCracks += pixels > 0;
  cracks_.worstView = std::max<uint64_t>(cracks_.worstView, pixels);
}

void CullVerifier::verifyView(const Camera& camera) {
  const bool reference = options_.referenceStride > 0 && viewIndex_ % options_.referenceStride == 0;
  ++viewIndex_;
  const bool occlusion = std::any_of(methods_.begin(), methods_.end(), [](const auto& m) {
    return m->method->stage == CullStage::Occlusion;
  });
  prepareTarget(camera, occlusion);
  const ViewTruth truth = drawTruth(camera, reference, occlusion);
  for (auto& m : methods_) verifyMethod(*m, camera, truth);
  // Last: it draws over the target the methods above read.
  if (options_.countCracks) countViewCracks(camera);
}

}  // namespace osd_cull::frame
