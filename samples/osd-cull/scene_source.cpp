#include "scene_source.h"

#include "adapters/scene_assets.h"
#include "adapters/scene_file.h"
#include "osd_cull/scene/default_scene.h"

#include <iostream>

namespace osd_cull::cli {

namespace {

bool isSequencePattern(const std::string& a) {
  return a.ends_with(".obj") &&
         (a.find('#') != std::string::npos || a.find('[') != std::string::npos);
}

// The loader's notes on each mesh (unknown tags, clamped sharpness ...), as the mesh form
// prints them: unusual input is never accepted silently.
scene::LoadedScene printNotes(scene::LoadedScene scene) {
  for (const scene::SceneMesh& m : scene.meshes)
    for (const std::string& note : m.notes)
      std::cout << "note: mesh '" << m.name << "': " << note << "\n";
  return scene;
}

}  // namespace

bool isSceneArgument(const std::string& argument) {
  return argument == "built-in:scene" || adapters::isSceneFile(argument) ||
         isSequencePattern(argument);
}

scene::LoadedScene loadSceneArgument(const std::string& argument, uint32_t frames) {
  if (argument == "built-in:scene") return scene::builtInScene(frames ? frames : 48);
  if (adapters::isSceneFile(argument)) return printNotes(adapters::loadScene(argument));
  scene::SceneDescription d;
  d.source = argument;
  scene::MeshDescription m;
  m.name = "sequence";
  m.animation.kind = scene::AnimationSource::Kind::Sequence;
  m.animation.pattern = argument;
  d.meshes.push_back(m);
  scene::InstanceDescription i;
  i.name = m.name;
  d.instances.push_back(i);
  d.views.emplace_back();
  d.views.back().name = "main";
  scene::LoadedScene s = adapters::loadScene(std::move(d));
  // Frame the first frame from the front (OBJ cages are mostly y up).
  const frame::Bounds b = s.meshes[0].restBounds;
  const glm::dvec3 c = b.center() + s.meshes[0].recentreOffset;
  scene::ViewDescription& v = s.description.views[0];
  v.up = {0.0, 1.0, 0.0};
  v.target = c;
  v.eye = c + glm::normalize(glm::dvec3(0.45, 0.35, 1.0)) * (3.0 * b.radius());
  if (frames == 0) s.description.settings.frameCount = 24;
  return printNotes(std::move(s));
}

}  // namespace osd_cull::cli
