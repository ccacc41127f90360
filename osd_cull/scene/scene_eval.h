#pragma once
/// \file scene_eval.h
/// \brief A scene description evaluated at a time: instance model matrices (parents,
/// spins, key frames) and view cameras (orbits, key frames, shadow views), all in double on
/// the host. The GPU never sees world coordinates: each instance is culled and drawn with
/// view · model composed here (frame::instanceCamera), so a mesh far from the origin keeps
/// the precision of one at the origin.

#include "osd_cull/frame/camera.h"
#include "osd_cull/scene/scene_description.h"

#include <vector>

namespace osd_cull::scene {

/// \brief The model matrix (object → world) of instance `index` at `seconds`: its parents'
/// matrices, then its own transform, spin and key-frame translation.
/// \throws osd_cull::Error for an index out of range or a parent cycle.
glm::dmat4 instanceMatrix(const SceneDescription& scene, size_t index, double seconds);

/// \brief Every instance's model matrix at `seconds`.
std::vector<glm::dmat4> instanceMatrices(const SceneDescription& scene, double seconds);

/// \brief The camera of `view` at `seconds`. `sceneBounds` (world) fits near and far planes
/// when the view gives none, and frames the shadow view.
/// \throws osd_cull::Error for a degenerate camera (eye on target, up along the view).
frame::Camera viewCamera(const ViewDescription& view, const SceneSettings& settings,
                         const frame::Bounds& sceneBounds, double seconds);

/// \brief World bounds of the points `objectBounds` (per instance, object space) moved by
/// the instances' matrices (all eight box corners).
frame::Bounds worldBounds(std::span<const frame::Bounds> objectBounds,
                          std::span<const glm::dmat4> models);

}  // namespace osd_cull::scene
