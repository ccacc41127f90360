#include "adapters/scene_assets.h"

#include "adapters/coordinate_limit.h"
#include "adapters/image_displacement.h"
#include "adapters/load_mesh.h"
#include "adapters/load_occluder.h"
#include "adapters/obj_sequence.h"
#include "adapters/scene_file.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_pass_displaced.h"
#include "osd_cull/frame/draw/triangle_mesh.h"
#include "osd_cull/scene/loaded_scene.h"
#include "osd_cull/scene/procedural.h"

#include <vector>

namespace osd_cull::adapters {

namespace {

using namespace osd_cull::scene;

frame::TriangleMesh loadOccluder(const OccluderDescription& o) {
  frame::TriangleMesh mesh =
      o.file.empty() ? frame::boxMesh(o.boxMin, o.boxMax) : loadTriangleMesh(o.file);
  for (glm::dvec3& p : mesh.positions) p = glm::dvec3(o.transform * glm::dvec4(p, 1.0));
  return mesh;
}

// Loads the map of a displaced mesh; errors name the scene file's JSON path of the
// displacement (the caller adds the file and the mesh name).
void displace(SceneMesh& mesh, const DisplacementDescription& d, size_t index) {
  const std::string path = "/meshes/" + std::to_string(index) + "/displacement";
  if (mesh.extraction.uvCorners.empty())
    throw Error(path +
                ": the mesh has no texture coordinates (OBJ vt lines) to look up its "
                "displacement map with");
  DisplacementOptions options;
  options.source = d.source;
  options.scale = d.scale;
  options.midlevel = d.midlevel;
  options.channel = d.channel;
  options.maxLod = d.maxLod;
  try {
    mesh.displacementMap.emplace(loadDisplacementMap(options));
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  mesh.displacedExtension = d.extension;
  mesh.displacedBox = d.box;
  mesh.validity = {false, frame::kDisplacedBackPatchNote};
}

// An instance whose transform shrinks its mesh to no size (a scale of 1e-300) is refused
// by name, with its extent, before a camera framed on it fails for want of a direction.
void checkInstanceExtents(const LoadedScene& scene) {
  for (size_t i = 0; i < scene.description.instances.size(); ++i) {
    const scene::InstanceDescription& inst = scene.description.instances[i];
    const SceneMesh& mesh = scene.meshes.at(inst.mesh);
    const glm::dmat4 model = patchModel(scene, i, 0.0);
    std::vector<glm::dvec3> corners;
    for (int c = 0; c < 8; ++c)
      corners.push_back(
          glm::dvec3(model * glm::dvec4(c & 1 ? mesh.restBounds.hi.x : mesh.restBounds.lo.x,
                                        c & 2 ? mesh.restBounds.hi.y : mesh.restBounds.lo.y,
                                        c & 4 ? mesh.restBounds.hi.z : mesh.restBounds.lo.z, 1.0)));
    if (auto problem = extentProblem(corners, "corners of its box in the world"))
      throw Error(scene.description.source + ": instance '" + inst.name + "' of mesh '" +
                  mesh.name + "': " + *problem + ": check the instance's transform and scale");
  }
}

}  // namespace

scene::LoadedScene loadScene(scene::SceneDescription description) {
  LoadedScene scene;
  for (const MeshDescription& m : description.meshes) {
    try {
      CageMesh cage;
      std::unique_ptr<CageAnimation> animation;
      if (m.animation.kind == AnimationSource::Kind::Sequence) {
        ObjSequence sequence = loadObjSequence(m.animation.pattern, m.animation.framesPerSecond);
        cage = std::move(sequence.firstFrame);
        animation = std::move(sequence.animation);
        if (m.scheme) cage.scheme = *m.scheme;
      } else if (!m.file.empty()) {
        LoadOptions options;
        options.scheme = m.scheme;
        cage = loadCage(m.file, options);
      } else {
        cage = *builtInMesh(m.builtIn);
        if (m.scheme) cage.scheme = *m.scheme;
      }
      if (!animation) animation = makeProceduralAnimation(m.animation, cage.positions);
      scene.meshes.push_back(
          makeSceneMesh(m.name, std::move(cage), m.patches, m.recentre, std::move(animation)));
      if (m.displacement) displace(scene.meshes.back(), *m.displacement, scene.meshes.size() - 1);
    } catch (const Error& e) {
      throw Error(description.source + ": mesh '" + m.name + "': " + e.what());
    }
  }
  for (const OccluderDescription& o : description.occluders)
    scene.occluders.push_back(loadOccluder(o));
  scene.description = std::move(description);
  checkInstanceExtents(scene);
  return scene;
}

scene::LoadedScene loadScene(const std::filesystem::path& sceneFile) {
  return loadScene(loadSceneFile(sceneFile));
}

}  // namespace osd_cull::adapters
