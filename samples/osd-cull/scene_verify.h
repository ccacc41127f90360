#pragma once
/// \file scene_verify.h
/// \brief `osd-cull verify SCENE.json|SEQUENCE --frames N --views V`: every cull method on
/// every instance of every frame, from the scene's own views and V random views of the
/// scene, checked against the double reference, the oracle and (optionally) the image.

#include "command.h"

namespace osd_cull::cli {

/// \brief The help text of the scene form of `verify`.
extern const char* const kSceneVerifyUsage;

/// \brief Runs the scene form of `verify` (the caller saw isSceneArgument()).
int verifyScene(Args& args);

}  // namespace osd_cull::cli
