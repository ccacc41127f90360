#pragma once
/// \file scene_source.h
/// \brief The SCENE argument of `osd-cull render` and `verify`: a scene file, an OBJ
/// sequence pattern, or the built-in scene.

#include "osd_cull/scene/loaded_scene.h"

#include <string>

namespace osd_cull::cli {

/// \brief Whether `argument` is a scene file (.json), a sequence pattern (an .obj name with
/// '#' digits or a [first-last] range) or "built-in:scene".
bool isSceneArgument(const std::string& argument);

/// \brief Loads the scene `argument` names. A sequence becomes a one-mesh scene with a
/// view framing its first frame. `frames` > 0 sets the built-in scene's length. Prints the
/// loader's notes on each mesh (SceneMesh::notes) as `note: mesh 'NAME': ...`.
/// \throws osd_cull::Error for files that do not load.
scene::LoadedScene loadSceneArgument(const std::string& argument, uint32_t frames);

}  // namespace osd_cull::cli
