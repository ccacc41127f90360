#include "osd_cull/scene/loaded_scene.h"

#include "osd_cull/error.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/scene_eval.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace osd_cull::scene {

std::unique_ptr<CageAnimation> makeProceduralAnimation(const AnimationSource& a,
                                                       std::span<const glm::dvec3> rest) {
  switch (a.kind) {
    case AnimationSource::Kind::None:
      return nullptr;
    case AnimationSource::Kind::Twist:
      return makeTwist(rest, a.deformer);
    case AnimationSource::Kind::Bend:
      return makeBend(rest, a.deformer);
    case AnimationSource::Kind::Wave:
      return makeWave(rest, a.deformer);
    case AnimationSource::Kind::Skin:
      return makeSkinning(rest, a.skinning);
    case AnimationSource::Kind::Sequence:
      break;
  }
  throw Error("an OBJ sequence is a file: load it with adapters::loadScene()");
}

namespace {

// The one recentring step of both forms: moves `points` by -offset, returns offset.
glm::dvec3 moveToOrigin(std::span<glm::dvec3> points, const glm::dvec3& offset) {
  if (offset != glm::dvec3(0.0))
    for (glm::dvec3& p : points) p -= offset;
  return offset;
}

}  // namespace

glm::dvec3 recentre(std::span<glm::dvec3> points) {
  return moveToOrigin(points, frame::boundsOf(points).center());
}

glm::dvec3 farMeshOffset(std::span<const glm::dvec3> points) {
  if (points.empty()) return glm::dvec3(0.0);
  const frame::Bounds b = frame::boundsOf(points);
  return glm::length(b.center()) > b.radius() ? b.center() : glm::dvec3(0.0);
}

glm::dvec3 recentreFar(std::span<glm::dvec3> points) {
  return moveToOrigin(points, farMeshOffset(points));
}

SceneMesh makeSceneMesh(std::string name, CageMesh cage, const PatchOptions& options, bool recentre,
                        std::unique_ptr<CageAnimation> animation) {
  SceneMesh m;
  m.name = std::move(name);
  if (recentre) m.recentreOffset = scene::recentre(cage.positions);
  bound::CullablePatches patches = bound::cullablePatches(cage, options);
  m.validity = std::move(patches.backPatch);
  m.extraction = std::move(patches.extraction);
  m.restCage = cage.positions;
  m.notes = cage.notes;
  m.restBounds = frame::boundsOf(m.extraction.patches.points);
  m.animation = std::move(animation);
  return m;
}

glm::dmat4 patchModel(const LoadedScene& scene, size_t index, double seconds) {
  const InstanceDescription& inst = scene.description.instances.at(index);
  return glm::translate(instanceMatrix(scene.description, index, seconds),
                        scene.meshes.at(inst.mesh).recentreOffset);
}

}  // namespace osd_cull::scene
