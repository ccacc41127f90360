#include "osd_cull/plan/scene_inputs.h"

#include "osd_cull/scene/scene_eval.h"

#include <map>

namespace osd_cull::plan {

std::string scenePlanKey(const scene::LoadedScene& scene, size_t view, size_t instance) {
  return scene.description.views.at(view).name + "/" + std::to_string(instance);
}

frame::Bounds posedBounds(const scene::LoadedScene& scene, size_t instance, double seconds) {
  const scene::InstanceDescription& inst = scene.description.instances.at(instance);
  const scene::SceneMesh& mesh = scene.meshes.at(inst.mesh);
  if (!mesh.animation) return mesh.restBounds;
  std::vector<glm::dvec3> cage(mesh.animation->vertexCount());
  mesh.animation->positions(seconds + inst.timeOffsetSeconds, cage);
  for (glm::dvec3& v : cage) v -= mesh.recentreOffset;
  std::vector<glm::dvec3> points(size_t(mesh.extraction.matrix.rowCount()));
  mesh.extraction.matrix.update(cage, points);
  return frame::boundsOf(points);
}

PlanInput instancePlanInput(const scene::LoadedScene& scene, size_t view, size_t instance,
                            std::span<const frame::Bounds> objectBounds,
                            std::span<const glm::dmat4> models, const frame::Camera& camera,
                            double tess, bool cageMoved) {
  const scene::SceneDescription& d = scene.description;
  const scene::SceneMesh& mesh = scene.meshes.at(d.instances.at(instance).mesh);
  PlanInput in;
  in.mesh = d.instances[instance].name.empty() ? mesh.name : d.instances[instance].name;
  in.view = d.views.at(view).name;
  in.bezier = mesh.extraction.patches.bezierCount;
  in.gregory = mesh.extraction.patches.gregoryCount;
  in.tess = tess;
  in.objectBounds = objectBounds[instance];
  in.model = models[instance];
  in.camera = camera;
  in.deforming = mesh.animation != nullptr;
  in.cageMoved = in.deforming && cageMoved;
  in.displaced = mesh.displacementMap.has_value();
  in.backPatchValidity = mesh.validity;
  in.occluders = !scene.occluders.empty();
  for (size_t j = 0; j < d.instances.size() && !in.occluders; ++j)
    in.occluders =
        j != instance && boxInView(objectBounds[j], models[j], camera) != BoxInView::Outside;
  // One cull frame per view culls every instance with one CullSettings: the scene form
  // keeps the default accuracy (the drawn-triangle bound) for all of them.
  in.ownAccuracy = false;
  return in;
}

std::vector<bool> selfOccluding(const scene::LoadedScene& scene) {
  std::map<size_t, bool> perMesh;
  std::vector<bool> out;
  for (const scene::InstanceDescription& inst : scene.description.instances) {
    auto it = perMesh.find(inst.mesh);
    if (it == perMesh.end()) {
      const scene::SceneMesh& mesh = scene.meshes.at(inst.mesh);
      it = perMesh.emplace(inst.mesh, mesh.animation || mayHideItself(mesh.extraction.patches))
               .first;
    }
    out.push_back(it->second);
  }
  return out;
}

std::vector<ScenePlanInput> scenePlanInputs(const scene::LoadedScene& scene, uint32_t frame,
                                            double tess) {
  const scene::SceneDescription& d = scene.description;
  const double t = d.settings.seconds(frame);
  std::vector<frame::Bounds> objectBounds;
  std::vector<glm::dmat4> models;
  for (size_t i = 0; i < d.instances.size(); ++i) {
    objectBounds.push_back(posedBounds(scene, i, t));
    models.push_back(scene::patchModel(scene, i, t));
  }
  std::vector<frame::Bounds> all = objectBounds;
  std::vector<glm::dmat4> allModels = models;
  for (const frame::TriangleMesh& m : scene.occluders) {
    all.push_back(frame::boundsOf(m.positions));
    allModels.emplace_back(1.0);
  }
  const frame::Bounds world = scene::worldBounds(all, allModels);
  const std::vector<bool> selfOccludes = selfOccluding(scene);
  std::vector<ScenePlanInput> out;
  for (size_t v = 0; v < d.views.size(); ++v) {
    const frame::Camera camera = scene::viewCamera(d.views[v], d.settings, world, t);
    for (size_t i = 0; i < d.instances.size(); ++i) {
      PlanInput in = instancePlanInput(scene, v, i, objectBounds, models, camera, tess, true);
      in.selfOccluding = selfOccludes[i];
      out.push_back({scenePlanKey(scene, v, i), v, i, std::move(in)});
    }
  }
  return out;
}

}  // namespace osd_cull::plan
