#include "osd_cull/session/mesh_session.h"

#include "osd_cull/bound/cull_reference.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/draw/renderer.h"

#include "shaders/shared/cull_layout.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace osd_cull::session {

StageCounts countByStage(std::span<const uint32_t> results) {
  StageCounts c;
  for (uint32_t code : results) {
    const uint32_t stage = bound::CullCode{code}.stage();
    c.frustum += stage == shader::kStageFrustum;
    c.backPatch += stage == shader::kStageBackPatch;
    c.occlusion += stage == shader::kStageOcclusion;
  }
  return c;
}

const char* toString(FrameKind kind) {
  switch (kind) {
    case FrameKind::Plain:
      return "plain";
    case FrameKind::OnePass:
      return "one-pass";
    case FrameKind::TwoPass:
      return "two-pass";
  }
  return "?";
}

std::string SessionSummary::text() const {
  char line[512];
  const double notDrawn = patches ? 100.0 * double(patches - drawn) / double(patches) : 0.0;
  std::snprintf(line, sizeof line,
                "summary: %u frames, mean %.2f ms, median %.2f ms; patches drawn %llu of %llu "
                "(%.1f%% not drawn), TES invocations %llu (about %llu saved)",
                frames, meanMs, medianMs, static_cast<unsigned long long>(drawn),
                static_cast<unsigned long long>(patches), notDrawn,
                static_cast<unsigned long long>(tesInvocations),
                static_cast<unsigned long long>(tesSaved));
  std::string text = line;
  if (predictedMeanMs > 0.0) {
    std::snprintf(line, sizeof line,
                  "\nsummary: plan changes %u, predicted %.2f ms against measured %.2f ms (mean)",
                  planChanges, predictedMeanMs, meanMs);
    text += line;
    if (configurations > 0) text += ", " + std::to_string(configurations) + " configurations built";
  }
  return text;
}

MeshSession::MeshSession(vulkan::Context& context, frame::Renderer& renderer,
                         frame::RenderTarget& target, frame::GpuPatchSet& gpu, const PatchSet& host,
                         std::span<const frame::GpuTriangleMesh* const> occluders,
                         MeshSessionOptions options, plan::Planner* planner)
    : context_(context),
      renderer_(renderer),
      target_(target),
      gpu_(gpu),
      host_(host),
      occluders_(occluders.begin(), occluders.end()),
      options_(std::move(options)),
      planner_(planner),
      objectBounds_(frame::boundsOf(host.points)) {
  if (options_.cachedConfigurations == 0)
    throw Error("mesh session: cachedConfigurations must be at least 1");
  if (planner_) {
    selfOccluding_ = plan::mayHideItself(host_);
  } else if (options_.frame.cull.frustum || !options_.frame.cull.backPatch.empty() ||
             !options_.frame.cull.occlusion.empty()) {
    last_ = &configuration("fixed", options_.frame);
  }
}

MeshSession::~MeshSession() = default;

const frame::CullPass* MeshSession::cullPass() const {
  if (!last_) return nullptr;
  return last_->frame ? last_->frame->cullPass(0) : last_->pass.get();
}

plan::PlanInput MeshSession::planInput(const frame::Camera& camera) const {
  plan::PlanInput in;
  in.mesh = options_.name;
  in.view = options_.view;
  in.bezier = host_.bezierCount;
  in.gregory = host_.gregoryCount;
  in.tess = plan::equivalentUniformLevel(host_, camera, glm::dmat4(1.0),
                                         options_.frame.render.tessellation);
  in.objectBounds = objectBounds_;
  in.camera = camera;
  in.displaced = options_.frame.cull.displacementMap != nullptr;
  in.deforming = in.cageMoved = options_.deforming;
  in.backPatchValidity = options_.frame.cull.backPatchValidity;
  in.occluders = options_.occluders || !occluders_.empty();
  in.selfOccluding = selfOccluding_;
  return in;
}

const vulkan::Buffer* MeshSession::cullData(const frame::CullSettings& cull) const {
  return options_.cullData && !cull.backPatch.empty() ? options_.cullData(cull.backPatch) : nullptr;
}

std::unique_ptr<frame::CullPass> MeshSession::makePass(const frame::CullSettings& cull) const {
  if (const vulkan::Buffer* data = cullData(cull))
    return std::make_unique<frame::CullPass>(context_, gpu_, host_, cull, *data);
  return std::make_unique<frame::CullPass>(context_, gpu_, host_, cull);
}

MeshSession::Configuration& MeshSession::configuration(const std::string& key,
                                                       const frame::CullFrameOptions& o) {
  const auto it = std::find_if(cache_.begin(), cache_.end(),
                               [&](const Configuration& c) { return c.key == key; });
  if (it != cache_.end()) {
    cache_.splice(cache_.begin(), cache_, it);  // most recently used first
    return cache_.front();
  }
  Configuration c;
  c.key = key;
  c.options = o;
  // A static mesh's points never move under the session: the one-pass stages may test the
  // precomputed per-patch boxes (CullSettings::staticPoints, docs/results/cull-kernel-floor.md).
  c.options.cull.staticPoints = !options_.deforming;
  if (!o.cull.occlusion.empty()) {
    // A planned configuration met for the first time starts with nothing visible: its
    // second pass draws the other stages' survivors (never every patch, as AllVisible's
    // first pass would); the fixed one keeps the options' policy.
    if (planner_) c.options.firstFrame = frame::FirstFrame::NoneVisible;
    const frame::CullMesh mesh[] = {{&gpu_, &host_, cullData(o.cull)}};
    c.frame = std::make_unique<frame::CullFrame>(context_, renderer_, target_, mesh, c.options);
  } else {
    c.pass = makePass(c.options.cull);
  }
  cache_.push_front(std::move(c));
  ++built_;
  // Drop the least recently used (never the one just made).
  while (cache_.size() > options_.cachedConfigurations) cache_.pop_back();
  return cache_.front();
}

SessionFrame MeshSession::draw(Configuration* c, const frame::Camera& camera,
                               const frame::CullFrameOptions& o) {
  SessionFrame f;
  f.index = next_;
  if (c && c->frame) {
    f.kind = FrameKind::TwoPass;
    f.stats = c->frame->render(camera, occluders_);
    return f;
  }
  const uint32_t n = host_.patchCount();
  if (c) {
    f.kind = FrameKind::OnePass;
    f.onePass = frame::renderCulled(renderer_, target_, camera, *c->pass, occluders_, o.render);
    const StageCounts counts = countByStage(c->pass->results());
    f.stats.culledFrustum = counts.frustum;
    f.stats.culledBackPatch = counts.backPatch;
    f.stats.clusters = c->pass->clusterCounts();
  } else {
    const frame::PatchDraw patches{&gpu_, &host_, 0};
    f.onePass = renderer_.render(target_, camera, {&patches, 1}, occluders_, o.render);
  }
  f.stats.patchesTotal = n;
  f.stats.drawnPass1 = f.onePass.patchesDrawn;
  f.stats.survivors = f.onePass.patchesDrawn;
  f.stats.pass1 = f.onePass.statistics;
  f.stats.frameMs = f.onePass.wallMs;
  if (f.onePass.gpuMs > 0.0) {
    // One render pass: the cull dispatch (OnePass) is inside its timestamps.
    f.stats.gpu.pass1 = f.stats.gpu.total = f.onePass.gpuMs;
    if (!c) f.stats.gpu.cull = f.stats.gpu.pyramid = f.stats.gpu.pass2 = 0.0;
  }
  return f;
}

SessionFrame MeshSession::render(const frame::Camera& camera) {
  frame::CullFrameOptions o = options_.frame;
  std::optional<plan::Plan> p;
  std::string key = "fixed";
  if (planner_) {
    p = planner_->plan(options_.name + "/" + options_.view, planInput(camera), next_);
    o = plan::applyPlan(*p, options_.frame);
    key = p->stages.describe() + "|" + p->displacement.choice;
  }
  const bool culls = o.cull.frustum || !o.cull.backPatch.empty() || !o.cull.occlusion.empty();
  Configuration* c = culls ? &configuration(key, o) : nullptr;
  SessionFrame f = draw(c, camera, o);
  last_ = c;
  if (p) {
    f.planChanged = !lastStages_ || !(*lastStages_ == p->stages);
    lastStages_ = p->stages;
    plan::Observation seen;
    seen.culledFrustum = f.stats.culledFrustum;
    seen.culledBackPatch = f.stats.culledBackPatch;
    seen.culledOcclusion = f.stats.culledOcclusion;
    seen.total = f.stats.patchesTotal;
    seen.ms = f.stats.frameMs;
    seen.drawn = f.stats.drawnPass1 + f.stats.drawnPass2;
    if (f.kind == FrameKind::TwoPass && f.stats.gpu.measured())
      seen.cullMs = f.stats.gpu.pyramid + f.stats.gpu.cull;
    planner_->observe(options_.name + "/" + options_.view, *p, seen);
    count(*p, camera, f);
    f.plan = std::move(p);
  }
  summary_.add(f.stats,
               f.plan
                   ? std::optional<double>(f.plan->predicted.totalMs() - f.plan->predicted.updateMs)
                   : std::nullopt,
               f.planChanged);
  summary_.setConfigurations(built_);
  ++next_;
  return f;
}

void MeshSession::count(const plan::Plan& p, const frame::Camera& camera, SessionFrame& f) {
  const auto start = std::chrono::steady_clock::now();
  for (const plan::StageChoice& stages : p.countOnly) {
    plan::Plan variant = p;
    variant.stages = stages;
    frame::CullFrameOptions o = plan::applyPlan(variant, options_.frame);
    o.cull.staticPoints = !options_.deforming;
    const std::unique_ptr<frame::CullPass> pass = makePass(o.cull);
    pass->run(camera, o.render.tessellation);
    planner_->observeCount(options_.name + "/" + options_.view, stages,
                           countByStage(pass->results()).backPatch, host_.patchCount());
    ++f.countingPasses;
  }
  f.countingMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

SessionSummary SummaryAccumulator::summary() const {
  SessionSummary s = summary_;
  if (!frameMs_.empty()) {
    std::vector<double> sorted = frameMs_;
    std::sort(sorted.begin(), sorted.end());
    const size_t n = sorted.size();  // an even count: the mean of the middle two
    s.medianMs = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  }
  return s;
}

void SummaryAccumulator::add(const frame::CullFrameStats& stats, std::optional<double> predictedMs,
                             bool planChanged) {
  SessionSummary& s = summary_;
  ++s.frames;
  s.meanMs += (stats.frameMs - s.meanMs) / s.frames;
  frameMs_.push_back(stats.frameMs);
  // Keep the per-frame times of long runs bounded: the median of the last 4,096+ frames.
  if (frameMs_.size() >= 8192) frameMs_.erase(frameMs_.begin(), frameMs_.begin() + 4096);
  const uint32_t drawn = stats.drawnPass1 + stats.drawnPass2;
  const uint32_t culled = stats.patchesTotal - std::min(stats.patchesTotal, drawn);
  const uint64_t tes =
      stats.pass1.tessEvaluationInvocations + stats.pass2.tessEvaluationInvocations;
  s.patches += stats.patchesTotal;
  s.drawn += drawn;
  s.tesInvocations += tes;
  if (drawn > 0) s.tesSaved += uint64_t(double(tes) / drawn * culled + 0.5);
  if (predictedMs) {
    s.planChanges += planChanged && s.frames > 1;
    predictedSum_ += *predictedMs;
    s.predictedMeanMs = predictedSum_ / ++planned_;
  }
}

}  // namespace osd_cull::session
