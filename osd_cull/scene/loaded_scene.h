#pragma once
/// \file loaded_scene.h
/// \brief A scene with its meshes refined into patches, ready to play: what
/// adapters::loadScene() makes of a scene file and scene::builtInScene() of the built-in one.

#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/bound/displaced_map.h"
#include "osd_cull/frame/camera.h"
#include "osd_cull/frame/draw/triangle_mesh.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/cage_animation.h"
#include "osd_cull/scene/scene_description.h"

#include <memory>
#include <optional>
#include <vector>

namespace osd_cull::scene {

/// \brief One mesh: its patches in object space (recentred), the cage → control-point
/// matrix, and its animation.
struct SceneMesh {
  std::string name;
  PatchExtraction extraction;        ///< rest-pose patches (recentred) and the matrix
  std::vector<glm::dvec3> restCage;  ///< the cage positions they came from (recentred)
  /// Subtracted from every cage position (the animation's too) at load; the instances'
  /// transforms add it back, so world positions are unchanged (SceneMeshDescription::recentre).
  glm::dvec3 recentreOffset{0.0};
  bound::BackPatchValidity validity;  ///< whether back-patch culling is valid on the cage
  /// What the loader ignored or found unusual in the cage (CageMesh::notes: unknown tags,
  /// negative sharpness clamped, ...): the commands print them, as for a mesh file.
  std::vector<std::string> notes;
  std::unique_ptr<CageAnimation> animation;  ///< null: static
  frame::Bounds restBounds;                  ///< of the rest-pose control points
  /// A displaced (static) mesh: its map, drawn along extraction.uvCorners; culled with the
  /// displaced bound `displacedExtension` applied to `displacedBox`.
  std::optional<bound::DisplacementMap> displacementMap;
  bound::DisplacedExtension displacedExtension = bound::DisplacedExtension::ACoN;
  bound::DisplacedBox displacedBox = bound::DisplacedBox::CAF;
};

/// \brief A description whose meshes and occluders are loaded.
struct LoadedScene {
  SceneDescription description;
  std::vector<SceneMesh> meshes;
  std::vector<frame::TriangleMesh> occluders;  ///< world coordinates
};

/// \brief The deformer `source` names (twist, bend, wave, skin) on the rest cage `rest`;
/// null for none. Sequences are files: adapters::loadScene() loads them.
/// \throws osd_cull::Error for a sequence, or as the deformer factories.
std::unique_ptr<CageAnimation> makeProceduralAnimation(const AnimationSource& source,
                                                       std::span<const glm::dvec3> rest);

/// \brief Subtracts the bounding-box centre of `points` from each of them and returns it:
/// the recentring of SceneMeshDescription::recentre, which keeps coordinates near the
/// origin so that their fp32 copies on the GPU keep the precision of the mesh's size.
glm::dvec3 recentre(std::span<glm::dvec3> points);

/// \brief The offset the mesh form (render, verify, view and plan MESH) recentres a mesh
/// by at load: the bounding-box centre of `points` when the origin lies outside their
/// bounding sphere (a mesh authored far from the origin, whose fp32 coordinates would lose
/// the precision the cull tests and the rasterizer need), else zero (the coordinates are
/// already as precise as the mesh's own size allows, and are left as authored). Empty
/// `points`: zero.
glm::dvec3 farMeshOffset(std::span<const glm::dvec3> points);

/// \brief The recentring of the mesh form (render, verify, view and plan MESH): recentres
/// `points` as recentre() does when farMeshOffset() is not zero, and returns that offset
/// (zero: `points` are left as authored). One code path with the scenes' recentre().
glm::dvec3 recentreFar(std::span<glm::dvec3> points);

/// \brief Fills a SceneMesh from a cage: recentres it (when `recentre`), refines it with
/// `options`, and records its validity and rest bounds. `animation` (may be null) must
/// produce the original, not recentred, positions.
SceneMesh makeSceneMesh(std::string name, CageMesh cage, const PatchOptions& options, bool recentre,
                        std::unique_ptr<CageAnimation> animation);

/// \brief The model matrix of instance `index`'s patches at `seconds`: the instance's world
/// matrix (scene_eval.h) times the translation by its mesh's recentreOffset.
glm::dmat4 patchModel(const LoadedScene& scene, size_t index, double seconds);

}  // namespace osd_cull::scene
