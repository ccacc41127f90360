#pragma once
/// \file default_scene.h
/// \brief The built-in scene of `osd-cull render` without a mesh, also used by tests and
/// benchmarks: several subdivision objects generated in code (the default mesh, a torus, a
/// pole sphere, a creased cube), a triangle wall and a ground slab, z up. Seen from the
/// default direction some objects are partly hidden behind others or the wall.

#include "osd_cull/frame/draw/triangle_mesh.h"
#include "osd_cull/patch/adaptive_patches.h"
#include "osd_cull/patch/patch_set.h"
#include "osd_cull/scene/loaded_scene.h"

#include <glm/vec3.hpp>

#include <vector>

namespace osd_cull::scene {

/// \brief Patches, triangle occluders and the default view of a scene.
struct Scene {
  PatchSet patches;
  std::vector<frame::TriangleMesh> occluders;
  glm::dvec3 up{0.0, 0.0, 1.0};
  glm::dvec3 viewDirection{0.55, -1.0, 0.45};  ///< from the scene center towards the eye
};

/// \brief The built-in scene, its cages extracted with `options`.
Scene defaultScene(const PatchOptions& options = {});

/// \brief The same objects as a scene description (docs/scene-format.md), each mesh an
/// instance placed by its transform, plus a standing character (scene::character()) in
/// front of the wall whose arms and legs swing (skinning, limb rig), with `frames` frames of a
/// camera path at 24 fps: a main view that swings around the objects and closes in.
SceneDescription defaultSceneDescription(uint32_t frames = 48);

/// \brief defaultSceneDescription() loaded (built-in cages only, no files).
LoadedScene builtInScene(uint32_t frames = 48);

}  // namespace osd_cull::scene
