#pragma once
/// \file scene_render.h
/// \brief `osd-cull render SCENE.json|SEQUENCE`: plays a scene (or an OBJ sequence) with
/// every view culled by its own two-pass frame, keeps each frame's image, and with
/// --compare reports what culling saved against the same frame drawn without it.

#include "command.h"

#include <string>

namespace osd_cull::cli {

/// \brief The help text of the scene form of `render`.
extern const char* const kSceneRenderUsage;

/// \brief Runs the scene form of `render` (the caller saw isSceneArgument()).
int renderScene(Args& args);

}  // namespace osd_cull::cli
