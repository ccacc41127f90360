#include "osd_cull/session/scene_player.h"

#include "osd_cull/session/mesh_session.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_methods.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/dynamic_patch_mesh.h"
#include "osd_cull/plan/scene_inputs.h"
#include "osd_cull/scene/scene_eval.h"

#include <array>
#include <chrono>
#include <map>
#include <optional>

namespace osd_cull::session {

// The control points one or more instances draw: a mesh's rest pose, or its pose at one
// time offset when it deforms.
struct ScenePlayer::Points {
  size_t mesh = 0;
  double timeOffset = 0.0;
  // A displaced mesh's map on the GPU (destroyed after the patch set that draws with it).
  std::unique_ptr<frame::GpuDisplacement> displacement;
  // A static mesh: its rest pose.
  PatchSet rest;
  std::unique_ptr<frame::GpuPatchSet> restGpu;
  // A deforming mesh: the cage input, control points and GPU bounds passes of
  // frame/dynamic_patch_mesh.h.
  std::unique_ptr<frame::DynamicPatchMesh> dynamic;
  std::vector<glm::dvec3> cage;   // scratch for the animation
  std::optional<double> posedAt;  // the mesh time of the current pose (deforming)
  frame::Bounds bounds;

  frame::GpuPatchSet& gpu() { return dynamic ? dynamic->gpu() : *restGpu; }
  const PatchSet& host() { return dynamic ? dynamic->patches() : rest; }
};

ScenePlayer::ScenePlayer(vulkan::Context& context, LoadedScene& scene,
                         const frame::CullFrameOptions& options, frame::PointUpdatePath pointUpdate,
                         plan::Planner* planner)
    : context_(context), scene_(scene), options_(options) {
  const SceneDescription& d = scene.description;
  if (d.instances.empty()) throw Error("scene " + d.source + ": no instances to draw");
  if (d.views.empty()) throw Error("scene " + d.source + ": no views");
  renderer_ = std::make_unique<frame::Renderer>(context);
  std::map<std::pair<size_t, double>, size_t> groups;
  for (const InstanceDescription& inst : d.instances) {
    const SceneMesh& mesh = scene.meshes.at(inst.mesh);
    const double offset = mesh.animation ? inst.timeOffsetSeconds : 0.0;
    auto [it, added] = groups.emplace(std::pair{inst.mesh, offset}, points_.size());
    if (added) {
      auto p = std::make_unique<Points>();
      p->mesh = inst.mesh;
      p->timeOffset = offset;
      if (mesh.animation) {
        p->dynamic = std::make_unique<frame::DynamicPatchMesh>(context, mesh.extraction,
                                                               mesh.restCage, pointUpdate);
      } else {
        p->rest = mesh.extraction.patches;
        p->restGpu = std::make_unique<frame::GpuPatchSet>(context, p->rest);
      }
      if (mesh.displacementMap) {
        p->displacement = std::make_unique<frame::GpuDisplacement>(
            context, *mesh.displacementMap, mesh.extraction.uvCorners,
            mesh.extraction.patches.patchCount());
        p->gpu().setDisplacement(p->displacement.get());
      }
      p->bounds = mesh.restBounds;
      points_.push_back(std::move(p));
    }
    instances_.push_back({it->second, glm::dmat4(1.0)});
  }
  for (const frame::TriangleMesh& m : scene.occluders) occluderMeshes_.emplace_back(context, m);
  for (const auto& m : occluderMeshes_) occluderPtrs_.push_back(&m);

  // A deforming mesh gets the cull data of the back-patch method in use (TCONE, NCONE, the
  // tangent plane's drawn-triangle bound) from the GPU bounds pass, recomputed on every frame
  // it moves (frame/cull/bounds_pass.h); a displaced one its displaced bound's cones.
  if (!options.cull.backPatch.empty()) {
    const bound::BackPatchMethod ref = frame::cullMethod(options.cull.backPatch).reference;
    if (frame::BoundsPass::hasCullData(ref)) backPatch_ = ref;
  }
  for (const ViewDescription& v : d.views) {
    View view;
    const uint32_t w = v.width ? v.width : d.settings.width;
    const uint32_t h = v.height ? v.height : d.settings.height;
    view.target = std::make_unique<frame::RenderTarget>(context, w, h);
    views_.push_back(std::move(view));
  }
  moved_.assign(points_.size(), false);
  setPlanner(planner);
  if (!planner)
    for (size_t v = 0; v < views_.size(); ++v) views_[v].frame = &fixedFrame(v);
}

frame::CullFrame& ScenePlayer::fixedFrame(size_t view) {
  View& v = views_.at(view);
  std::unique_ptr<frame::CullFrame>& f = v.frames[""];
  if (!f) {
    std::vector<frame::CullMesh> meshes;
    for (size_t i = 0; i < instances_.size(); ++i) meshes.push_back(cullMesh(i, nullptr, nullptr));
    f = std::make_unique<frame::CullFrame>(context_, *renderer_, *v.target, meshes, options_);
  }
  return *f;
}

frame::CullMesh ScenePlayer::cullMesh(size_t i, const frame::CullStages* stages,
                                      const frame::CullMethod::Displaced* kernel) {
  const Instance& inst = instances_[i];
  Points& p = *points_[inst.points];
  const SceneMesh& mesh = scene_.meshes[p.mesh];
  frame::CullMesh m{
      .gpu = &p.gpu(), .host = &p.host(), .model = inst.model, .backPatchValidity = mesh.validity};
  m.cullBackFaces = mesh.validity.enabled;  // per mesh, in every mode (like for like)
  if (stages) m.stages = *stages;
  if (mesh.displacementMap) {
    m.displacementMap = &*mesh.displacementMap;
    m.uvCorners = mesh.extraction.uvCorners;
    m.displacedKernel = {mesh.displacedExtension, mesh.displacedBox};
    // A planned displaced bound (Niessner & Loop Table 1) replaces the scene's.
    if (kernel) m.displacedKernel = *kernel;
  }
  const std::string& method = stages ? stages->backPatch : options_.cull.backPatch;
  // The cone method whose cull data the bounds pass recomputes (the options' or the plan's).
  bool cone = backPatch_.has_value();
  bound::BackPatchMethod coneMethod = backPatch_.value_or(bound::BackPatchMethod{});
  if (stages) {
    cone = false;
    if (!method.empty()) {
      coneMethod = frame::cullMethod(method).reference;
      cone = frame::BoundsPass::hasCullData(coneMethod);
    }
  }
  // The bounds passes of a deforming mesh are made on first use: a mesh planned without a
  // cone method never runs one.
  if (p.dynamic && mesh.displacementMap) {
    m.cullData = &p.dynamic->displacedCullData(*mesh.displacementMap, mesh.extraction.uvCorners,
                                               m.displacedKernel.extension);
  } else if (p.dynamic && mesh.validity.enabled) {
    if (cone)
      m.cullData = &p.dynamic->cullData(coneMethod);
    else if (!method.empty())
      m.backPatchValidity = bound::BackPatchValidity{
          false, "mesh '" + mesh.name + "' deforms; the bounds pass recomputes cull data for " +
                     "tcone, ncone and the tangent plane only"};
  }
  return m;
}

ScenePlayer::~ScenePlayer() = default;

uint32_t ScenePlayer::patchCount() const {
  uint32_t n = 0;
  for (const Instance& i : instances_) n += points_[i.points]->host().patchCount();
  return n;
}

const PatchSet& ScenePlayer::patches(size_t i) const {
  return points_.at(instances_.at(i).points)->host();
}

void ScenePlayer::seek(uint32_t frameIndex) {
  const SceneDescription& d = scene_.description;
  const double t = d.settings.seconds(frameIndex);
  moved_.assign(points_.size(), false);
  for (size_t k = 0; k < points_.size(); ++k) {
    const std::unique_ptr<Points>& p = points_[k];
    const SceneMesh& mesh = scene_.meshes[p->mesh];
    // A static mesh is never re-evaluated; a deforming one only when its time changed, and
    // then DynamicPatchMesh::update() recomputes its points and its bounds-pass cull data.
    if (!mesh.animation || p->posedAt == t + p->timeOffset) continue;
    moved_[k] = true;
    p->posedAt = t + p->timeOffset;
    p->cage.resize(mesh.animation->vertexCount());
    mesh.animation->positions(t + p->timeOffset, p->cage);
    for (glm::dvec3& v : p->cage) v -= mesh.recentreOffset;
    p->dynamic->setCagePositions(p->cage);
    p->dynamic->update();
    p->bounds = frame::boundsOf(p->dynamic->patches().points);
  }
  std::vector<frame::Bounds> objectBounds;
  std::vector<glm::dmat4> models;
  for (size_t i = 0; i < instances_.size(); ++i) {
    instances_[i].model = patchModel(scene_, i, t);
    objectBounds.push_back(points_[instances_[i].points]->bounds);
    models.push_back(instances_[i].model);
  }
  for (const frame::TriangleMesh& m : scene_.occluders) {
    objectBounds.push_back(frame::boundsOf(m.positions));
    models.emplace_back(1.0);
  }
  bounds_ = scene::worldBounds(objectBounds, models);
  for (size_t v = 0; v < views_.size(); ++v) {
    views_[v].camera = viewCamera(d.views[v], d.settings, bounds_, t);
    if (views_[v].frame)
      for (size_t i = 0; i < instances_.size(); ++i)
        views_[v].frame->setModel(i, instances_[i].model);
  }
}

void ScenePlayer::setPlanner(plan::Planner* planner) {
  planner_ = planner;
  if (planner && selfOccluding_.empty()) selfOccluding_ = plan::selfOccluding(scene_);
  for (View& v : views_) v.frame = v.frames.count("") ? v.frames.at("").get() : nullptr;
}

frame::CullFrame& ScenePlayer::cullFrame(size_t view) {
  if (!planner_ && !views_.at(view).frame) views_[view].frame = &fixedFrame(view);
  frame::CullFrame* f = views_.at(view).frame;
  if (!f)
    throw Error("ScenePlayer::cullFrame: view '" + scene_.description.views.at(view).name +
                "' has not been culled yet (its plan draws it without culling)");
  return *f;
}

std::vector<ViewFrame> ScenePlayer::render(uint32_t frameIndex) {
  seek(frameIndex);
  return renderCurrent(frameIndex);
}

void ScenePlayer::setCamera(size_t view, const frame::Camera& camera) {
  views_.at(view).camera = camera;
}

std::vector<ViewFrame> ScenePlayer::renderCurrent(uint64_t planFrame) {
  std::vector<ViewFrame> out;
  for (size_t v = 0; v < views_.size(); ++v) {
    if (planner_) {
      out.push_back(renderPlanned(v, planFrame));
      continue;
    }
    views_[v].frame = &fixedFrame(v);
    for (size_t i = 0; i < instances_.size(); ++i)
      views_[v].frame->setModel(i, instances_[i].model);
    out.push_back({scene_.description.views[v].name, views_[v].camera,
                   views_[v].frame->render(views_[v].camera, occluderPtrs_)});
  }
  return out;
}

namespace {

frame::CullStages cullStages(const plan::StageChoice& c) {
  return {c.frustum, c.backPatch, c.occlusion};
}

}  // namespace

frame::CullFrame& ScenePlayer::plannedFrame(size_t view, const std::vector<plan::Plan>& plans,
                                            bool& built) {
  // The frame-wide options of the choices: two-pass unless every occluding instance is
  // planned aggressive, Hi-Z at full resolution when one asks for it.
  frame::CullFrameOptions o = options_;
  bool occlusion = false, aggressive = true, full = false;
  std::string key;
  for (const plan::Plan& p : plans) {
    key += p.stages.describe() + (p.displacement.on ? " " + p.displacement.choice : "") + ";";
    if (p.stages.occlusion.empty()) continue;
    occlusion = true;
    aggressive = aggressive && p.stages.aggressive;
    full = full || p.stages.hizFull;
  }
  o.aggressive = occlusion && aggressive;
  o.hiz.fullResolution = full;
  // A set of choices met for the first time starts with nothing visible: its second pass
  // draws the other stages' survivors, never every patch (issue 18).
  o.firstFrame = frame::FirstFrame::NoneVisible;
  key += o.aggressive ? "aggressive" : "two-pass";
  key += full ? ", full" : ", half";
  View& v = views_.at(view);
  auto it = v.frames.find(key);
  built = it == v.frames.end();
  if (built) {
    std::vector<frame::CullMesh> meshes;
    for (size_t i = 0; i < instances_.size(); ++i) {
      const frame::CullStages stages = cullStages(plans[i].stages);
      // The displaced bound the plan's frustum and occlusion stages test (applyPlan).
      std::optional<frame::CullMethod::Displaced> kernel;
      if (const SceneMesh& mesh = scene_.meshes[points_[instances_[i].points]->mesh];
          mesh.displacementMap && plans[i].displacement.on && plans[i].culls()) {
        frame::CullFrameOptions withMap = options_;
        withMap.cull.displacementMap = &*mesh.displacementMap;
        withMap.cull.displacedKernel = {mesh.displacedExtension, mesh.displacedBox};
        kernel = plan::applyPlan(plans[i], withMap).cull.displacedKernel;
      }
      meshes.push_back(cullMesh(i, &stages, kernel ? &*kernel : nullptr));
    }
    it = v.frames
             .emplace(key, std::make_unique<frame::CullFrame>(context_, *renderer_, *v.target,
                                                              meshes, o))
             .first;
    ++v.built;
  } else if (o.aggressive && it->second.get() != v.frame) {
    // Kept from earlier frames, its status is stale: the aggressive mode draws only what it
    // holds visible, so start over (two passes re-test every patch and need no reset).
    it->second->reset(o.firstFrame);
  }
  v.frame = it->second.get();
  // Most recent first; the least recently used beyond cachedFrames_ goes (never this one).
  v.recent.remove(key);
  v.recent.push_front(key);
  while (v.recent.size() > cachedFrames_) {
    v.frames.erase(v.recent.back());
    v.recent.pop_back();
  }
  return *v.frame;
}

void ScenePlayer::setCachedFrames(size_t frames) {
  if (frames == 0) throw Error("scene player: at least one cull frame per view must be kept");
  cachedFrames_ = frames;
}

ViewFrame ScenePlayer::renderPlanned(size_t view, uint64_t frameIndex) {
  View& v = views_.at(view);
  ViewFrame out{scene_.description.views.at(view).name, v.camera, {}, {}, true};
  std::vector<frame::Bounds> objectBounds;
  std::vector<glm::dmat4> models;
  for (const Instance& i : instances_) {
    objectBounds.push_back(points_[i.points]->bounds);
    models.push_back(i.model);
  }
  bool culls = false;
  for (size_t i = 0; i < instances_.size(); ++i) {
    // An adaptive tessellation is planned as the uniform level of the same work.
    const double tess = plan::equivalentUniformLevel(patches(i), v.camera, instances_[i].model,
                                                     options_.render.tessellation);
    plan::PlanInput in = plan::instancePlanInput(scene_, view, i, objectBounds, models, v.camera,
                                                 tess, moved_[instances_[i].points]);
    in.selfOccluding = selfOccluding_[i];
    out.plans.push_back(planner_->plan(plan::scenePlanKey(scene_, view, i), in, frameIndex));
    culls = culls || out.plans.back().culls();
  }
  // Per instance: culled by frustum, back-patch and occlusion stage.
  std::vector<std::array<uint32_t, 3>> culled(instances_.size(), {0, 0, 0});
  bool built = false;  // a CullFrame built this frame: its time includes the pipelines
  if (!culls) {
    // No instance culls: the plain renderer draws the view, no cull pass, no pyramid.
    out.culled = false;
    const frame::FrameStats plain = drawUnculled(view, *v.target);
    out.stats.patchesTotal = patchCount();
    out.stats.drawnPass1 = plain.patchesDrawn;
    out.stats.survivors = plain.patchesDrawn;
    out.stats.pass1 = plain.statistics;
    out.stats.frameMs = plain.wallMs;
  } else {
    frame::CullFrame& f = plannedFrame(view, out.plans, built);
    for (size_t i = 0; i < instances_.size(); ++i) f.setModel(i, instances_[i].model);
    out.stats = f.render(v.camera, occluderPtrs_);
    for (size_t i = 0; i < instances_.size(); ++i)
      if (out.plans[i].culls()) {
        const StageCounts c = countByStage(f.readResults(i));
        culled[i] = {c.frustum, c.backPatch, c.occlusion};
      }
  }
  // Learn: each instance's rates, and the view's frame time shared in proportion to what
  // each instance was predicted to cost (the point update is not part of it; a frame that
  // built its CullFrame, pipelines included, teaches no time).
  double predicted = 0.0;
  for (const plan::Plan& p : out.plans) predicted += p.predicted.totalMs() - p.predicted.updateMs;
  for (size_t i = 0; i < instances_.size(); ++i) {
    const plan::Plan& p = out.plans[i];
    const double share =
        predicted > 0.0 && !built
            ? (p.predicted.totalMs() - p.predicted.updateMs) / predicted * out.stats.frameMs
            : 0.0;
    plan::Observation seen;
    seen.culledFrustum = culled[i][0];
    seen.culledBackPatch = culled[i][1];
    seen.culledOcclusion = culled[i][2];
    seen.total = points_[instances_[i].points]->host().patchCount();
    seen.ms = share;
    // The view's cull work (pyramid, kernels, status), shared the same way.
    if (out.culled && out.stats.gpu.measured() && out.stats.frameMs > 0.0)
      seen.cullMs = share / out.stats.frameMs * (out.stats.gpu.pyramid + out.stats.gpu.cull);
    planner_->observe(plan::scenePlanKey(scene_, view, i), p, seen);
  }
  count(view, out);
  return out;
}

void ScenePlayer::count(size_t view, ViewFrame& out) {
  const auto start = std::chrono::steady_clock::now();
  const View& v = views_.at(view);
  for (size_t i = 0; i < instances_.size(); ++i) {
    const plan::Plan& p = out.plans[i];
    // A deforming mesh's cull data of another cone method would need a bounds pass of its
    // own on every frame from then on: its variants keep borrowing a sibling's rate
    // (Planner::rate).
    if (p.countOnly.empty() || points_[instances_[i].points]->dynamic) continue;
    for (const plan::StageChoice& stages : p.countOnly) {
      plan::Plan variant = p;
      variant.stages = stages;
      const frame::CullSettings planned = plan::applyPlan(variant, options_).cull;
      const frame::CullStages s = cullStages(stages);
      const frame::CullMesh m = cullMesh(i, &s, nullptr);
      // The settings CullFrame gives this mesh's batch, without occlusion: the pass culls
      // nothing that is drawn and touches no visibility status.
      frame::CullSettings settings = planned;
      settings.frustum = stages.frustum;
      settings.backPatch = stages.backPatch;
      settings.occlusion.clear();
      if (m.backPatchValidity) settings.backPatchValidity = *m.backPatchValidity;
      if (m.displacementMap) {
        settings.displacementMap = m.displacementMap;
        settings.uvCorners = m.uvCorners;
        settings.displacedKernel = m.displacedKernel;
      }
      settings.staticPoints = m.displacementMap == nullptr;
      frame::CullPass pass(context_, *m.gpu, *m.host, settings);
      pass.run(frame::instanceCamera(v.camera, m.model), options_.render.tessellation);
      planner_->observeCount(plan::scenePlanKey(scene_, view, i), stages,
                             countByStage(pass.results()).backPatch, m.host->patchCount());
      ++out.countingPasses;
    }
  }
  out.countingMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

frame::FrameStats ScenePlayer::renderUnculled(size_t view, frame::RenderTarget& target) {
  return drawUnculled(view, target);
}

frame::FrameStats ScenePlayer::drawUnculled(size_t view, frame::RenderTarget& target) {
  const View& v = views_.at(view);
  std::vector<frame::PatchDraw> draws;
  uint32_t base = 0;
  for (const Instance& i : instances_) {
    Points& p = *points_[i.points];
    frame::PatchDraw draw{&p.gpu(), &p.host(), base};
    draw.model = &i.model;
    draw.cullBackFaces = scene_.meshes[p.mesh].validity.enabled;
    draws.push_back(draw);
    base += p.host().patchCount();
  }
  frame::RenderOptions o = options_.render;
  o.clear = true;
  return renderer_->render(target, v.camera, draws, occluderPtrs_, o);
}

UnculledComparison ScenePlayer::compareWithUnculled(size_t view, frame::RenderTarget& scratch) {
  frame::RenderTarget& culled = target(view);
  if (scratch.width() != culled.width() || scratch.height() != culled.height())
    throw Error("ScenePlayer::compareWithUnculled: the scratch target is " +
                std::to_string(scratch.width()) + "x" + std::to_string(scratch.height()) +
                ", view " + std::to_string(view) + " renders " + std::to_string(culled.width()) +
                "x" + std::to_string(culled.height()));
  UnculledComparison c;
  c.unculled = renderUnculled(view, scratch);
  c.items = frame::compareItems(culled.readItems(context_), scratch.readItems(context_));
  return c;
}

uint32_t ScenePlayer::users(const Points& points) const {
  uint32_t n = 0;
  for (const Instance& i : instances_) n += points_[i.points].get() == &points;
  return n;
}

std::vector<MeshWork> ScenePlayer::work() const {
  std::vector<MeshWork> out;
  for (const auto& p : points_) {
    MeshWork w{.mesh = scene_.meshes[p->mesh].name,
               .deforms = p->dynamic != nullptr,
               .instances = users(*p)};
    if (p->dynamic) {
      const frame::DynamicMeshCounters c = p->dynamic->counters();
      w.pointUpdates = c.pointUpdates;
      w.boundsDispatches = c.boundsDispatches;
    }
    out.push_back(w);
  }
  return out;
}

const frame::GpuPatchSet& ScenePlayer::gpuPatches(size_t i) const {
  return points_.at(instances_.at(i).points)->gpu();
}

frame::DynamicPatchMesh* ScenePlayer::dynamicMesh(size_t i) {
  return points_.at(instances_.at(i).points)->dynamic.get();
}

std::vector<std::string> ScenePlayer::describe() const {
  std::vector<std::string> lines;
  for (const auto& p : points_) {
    const SceneMesh& mesh = scene_.meshes[p->mesh];
    const PatchSet& host = p->host();
    std::string line = "mesh '" + mesh.name + "': " + std::to_string(host.bezierCount) +
                       " Bezier + " + std::to_string(host.gregoryCount) + " Gregory patches, " +
                       std::to_string(users(*p)) + " instance(s) share its points";
    line += mesh.animation ? ", deforms (" + mesh.animation->describe() + ")" : ", static";
    if (mesh.displacementMap)
      line += ", displaced (" + mesh.displacementMap->name() + ", scale " +
              std::to_string(mesh.displacementMap->scale()) + ", culled with " +
              bound::displacedKernelName(mesh.displacedExtension, mesh.displacedBox) +
              "; back-patch culling off)";
    if (glm::length(mesh.recentreOffset) > 0.0) {
      const glm::dvec3& o = mesh.recentreOffset;
      line += ", recentred by (" + std::to_string(o.x) + ", " + std::to_string(o.y) + ", " +
              std::to_string(o.z) + ")";
    }
    lines.push_back(line);
  }
  return lines;
}

}  // namespace osd_cull::session
