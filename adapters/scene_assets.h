#pragma once
/// \file scene_assets.h
/// \brief Loads what a scene description names: cage files or built-in cages (refined into
/// patches, recentred), their animations, and the triangle occluders.

#include "osd_cull/scene/loaded_scene.h"

#include <filesystem>

namespace osd_cull::adapters {

/// \brief Loads every mesh, animation and occluder of `description`.
/// \throws osd_cull::Error naming the mesh (and file) that failed to load or refine.
scene::LoadedScene loadScene(scene::SceneDescription description);

/// \brief loadSceneFile() then loadScene().
scene::LoadedScene loadScene(const std::filesystem::path& sceneFile);

}  // namespace osd_cull::adapters
