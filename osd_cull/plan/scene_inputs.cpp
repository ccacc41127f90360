#include "osd_cull/plan/scene_inputs.h"

#include "osd_cull/scene/scene_eval.h"

namespace osd_cull::plan {

std::vector<ScenePlanInput> scenePlanInputs(const scene::LoadedScene& scene, uint32_t frame,
                                            double tess) {
  const scene::SceneDescription& d = scene.description;
  const double t = d.settings.seconds(frame);
  std::vector<frame::Bounds> objectBounds;
  std::vector<glm::dmat4> models;
  for (size_t i = 0; i < d.instances.size(); ++i) {
    objectBounds.push_back(scene.meshes.at(d.instances[i].mesh).restBounds);
    models.push_back(scene::patchModel(scene, i, t));
  }
  std::vector<frame::Bounds> all = objectBounds;
  std::vector<glm::dmat4> allModels = models;
  for (const frame::TriangleMesh& m : scene.occluders) {
    all.push_back(frame::boundsOf(m.positions));
    allModels.emplace_back(1.0);
  }
  const frame::Bounds world = scene::worldBounds(all, allModels);
  std::vector<ScenePlanInput> out;
  for (size_t v = 0; v < d.views.size(); ++v) {
    frame::Camera camera = scene::viewCamera(d.views[v], d.settings, world, t);
    for (size_t i = 0; i < d.instances.size(); ++i) {
      const scene::SceneMesh& mesh = scene.meshes.at(d.instances[i].mesh);
      PlanInput in;
      in.mesh = d.instances[i].name.empty() ? mesh.name : d.instances[i].name;
      in.view = d.views[v].name;
      in.bezier = mesh.extraction.patches.bezierCount;
      in.gregory = mesh.extraction.patches.gregoryCount;
      in.tess = tess;
      in.objectBounds = objectBounds[i];
      in.model = models[i];
      in.camera = camera;
      in.deforming = in.cageMoved = mesh.animation != nullptr;
      in.backPatchValidity = mesh.validity;
      in.occluders = !scene.occluders.empty() || d.instances.size() > 1;
      out.push_back({in.view + "/" + std::to_string(i), v, i, std::move(in)});
    }
  }
  return out;
}

}  // namespace osd_cull::plan
