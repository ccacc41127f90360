#include "adapters/scene_assets.h"

#include "adapters/load_mesh.h"
#include "adapters/load_occluder.h"
#include "adapters/scene_file.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/draw/triangle_mesh.h"
#include "osd_cull/scene/procedural.h"

namespace osd_cull::adapters {

namespace {

using namespace osd_cull::scene;

std::unique_ptr<CageAnimation> makeAnimation(const MeshDescription& m,
                                             std::span<const glm::dvec3> rest) {
  switch (m.animation.kind) {
    case AnimationSource::Kind::None:
      return nullptr;
    default:
      // The deformers and OBJ sequences (scene/cage_animation.h) belong to the animation
      // part of issue 10 and are not in this build yet.
      throw Error("mesh '" + m.name + "': animation '" + toString(m.animation.kind) +
                  "' is not available in this build yet");
  }
  (void)rest;
}

frame::TriangleMesh loadOccluder(const OccluderDescription& o) {
  frame::TriangleMesh mesh =
      o.file.empty() ? frame::boxMesh(o.boxMin, o.boxMax) : loadTriangleMesh(o.file);
  for (glm::dvec3& p : mesh.positions) p = glm::dvec3(o.transform * glm::dvec4(p, 1.0));
  return mesh;
}

}  // namespace

scene::LoadedScene loadScene(scene::SceneDescription description) {
  LoadedScene scene;
  for (const MeshDescription& m : description.meshes) {
    try {
      CageMesh cage;
      if (m.animation.kind == AnimationSource::Kind::Sequence) {
        throw Error("OBJ sequences are not available in this build yet");
      } else if (!m.file.empty()) {
        LoadOptions options;
        options.scheme = m.scheme;
        cage = loadCage(m.file, options);
      } else {
        cage = *builtInMesh(m.builtIn);
        if (m.scheme) cage.scheme = *m.scheme;
      }
      auto animation = makeAnimation(m, cage.positions);
      scene.meshes.push_back(
          makeSceneMesh(m.name, std::move(cage), m.patches, m.recentre, std::move(animation)));
    } catch (const Error& e) {
      throw Error(description.source + ": mesh '" + m.name + "': " + e.what());
    }
  }
  for (const OccluderDescription& o : description.occluders)
    scene.occluders.push_back(loadOccluder(o));
  scene.description = std::move(description);
  return scene;
}

scene::LoadedScene loadScene(const std::filesystem::path& sceneFile) {
  return loadScene(loadSceneFile(sceneFile));
}

}  // namespace osd_cull::adapters
