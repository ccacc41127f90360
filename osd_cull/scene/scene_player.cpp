#include "osd_cull/scene/scene_player.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_methods.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/dynamic_patch_mesh.h"
#include "osd_cull/scene/scene_eval.h"

#include <map>
#include <optional>

namespace osd_cull::scene {

// The control points one or more instances draw: a mesh's rest pose, or its pose at one
// time offset when it deforms.
struct ScenePlayer::Points {
  size_t mesh = 0;
  double timeOffset = 0.0;
  // A static mesh: its rest pose, and its displacement when it has a map (destroyed after
  // the patch set that draws with it).
  PatchSet rest;
  std::unique_ptr<frame::GpuDisplacement> displacement;
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
                         const frame::CullFrameOptions& options, frame::PointUpdatePath pointUpdate)
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
        if (mesh.displacementMap) {
          p->displacement = std::make_unique<frame::GpuDisplacement>(
              context, *mesh.displacementMap, mesh.extraction.uvCorners, p->rest.patchCount());
          p->restGpu->setDisplacement(p->displacement.get());
        }
      }
      p->bounds = mesh.restBounds;
      points_.push_back(std::move(p));
    }
    instances_.push_back({it->second, glm::dmat4(1.0)});
  }
  for (const frame::TriangleMesh& m : scene.occluders) occluderMeshes_.emplace_back(context, m);
  for (const auto& m : occluderMeshes_) occluderPtrs_.push_back(&m);

  // A deforming mesh gets its cones from the GPU bounds pass of the cone method in use; the
  // tangent plane's drawn-triangle data is built on the host only, so it stays off there.
  std::optional<bound::BackPatchMethod> coneMethod;
  if (!options.cull.backPatch.empty()) {
    const bound::BackPatchMethod ref = frame::cullMethod(options.cull.backPatch).reference;
    if (ref == bound::BackPatchMethod::TCone || ref == bound::BackPatchMethod::NCone)
      coneMethod = ref;
  }
  std::vector<frame::CullMesh> meshes;
  for (const Instance& inst : instances_) {
    Points& p = *points_[inst.points];
    const SceneMesh& mesh = scene.meshes[p.mesh];
    frame::CullMesh m{.gpu = &p.gpu(),
                      .host = &p.host(),
                      .model = inst.model,
                      .backPatchValidity = mesh.validity};
    if (mesh.displacementMap) {
      m.displacementMap = &*mesh.displacementMap;
      m.uvCorners = mesh.extraction.uvCorners;
      m.displacedKernel = {mesh.displacedExtension, mesh.displacedBox};
    }
    if (p.dynamic && mesh.validity.enabled) {
      if (coneMethod)
        m.cullData = &p.dynamic->cullData(*coneMethod);
      else if (!options.cull.backPatch.empty())
        m.backPatchValidity = bound::BackPatchValidity{
            false, "mesh '" + mesh.name + "' deforms; its bounds are recomputed per frame for " +
                       "tcone and ncone only"};
    }
    meshes.push_back(std::move(m));
  }
  for (const ViewDescription& v : d.views) {
    View view;
    const uint32_t w = v.width ? v.width : d.settings.width;
    const uint32_t h = v.height ? v.height : d.settings.height;
    view.target = std::make_unique<frame::RenderTarget>(context, w, h);
    view.frame =
        std::make_unique<frame::CullFrame>(context, *renderer_, *view.target, meshes, options);
    views_.push_back(std::move(view));
  }
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
  for (auto& p : points_) {
    const SceneMesh& mesh = scene_.meshes[p->mesh];
    // A static mesh is never re-evaluated; a deforming one only when its time changed, and
    // then DynamicPatchMesh::update() recomputes its points and its bounds-pass cull data.
    if (!mesh.animation || p->posedAt == t + p->timeOffset) continue;
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
  bounds_ = worldBounds(objectBounds, models);
  for (size_t v = 0; v < views_.size(); ++v) {
    views_[v].camera = viewCamera(d.views[v], d.settings, bounds_, t);
    for (size_t i = 0; i < instances_.size(); ++i)
      views_[v].frame->setModel(i, instances_[i].model);
  }
}

std::vector<ViewFrame> ScenePlayer::render(uint32_t frameIndex) {
  seek(frameIndex);
  std::vector<ViewFrame> out;
  for (size_t v = 0; v < views_.size(); ++v)
    out.push_back({scene_.description.views[v].name, views_[v].camera,
                   views_[v].frame->render(views_[v].camera, occluderPtrs_)});
  return out;
}

frame::FrameStats ScenePlayer::renderUnculled(size_t view, frame::RenderTarget& target) {
  const View& v = views_.at(view);
  std::vector<frame::PatchDraw> draws;
  uint32_t base = 0;
  for (const Instance& i : instances_) {
    Points& p = *points_[i.points];
    frame::PatchDraw draw{&p.gpu(), &p.host(), base};
    draw.model = &i.model;
    draws.push_back(draw);
    base += p.host().patchCount();
  }
  frame::RenderOptions o = v.frame->options().render;
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
  const std::vector<uint32_t> a = culled.readItems(context_);
  const std::vector<uint32_t> b = scratch.readItems(context_);
  c.pixels = a.size();
  for (size_t p = 0; p < a.size(); ++p) {
    c.covered += b[p] != 0;
    c.lost += b[p] != 0 && a[p] == 0;
    c.differing += a[p] != b[p];
  }
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

}  // namespace osd_cull::scene
