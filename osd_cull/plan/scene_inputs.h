#pragma once
/// \file scene_inputs.h
/// \brief The plan inputs of a loaded scene at one frame: one PlanInput per view and
/// instance, with the instance's model matrix and the view's camera as the ScenePlayer
/// places them (scene_eval.h), so a plan can be made and printed without a device.

#include "osd_cull/plan/planner.h"
#include "osd_cull/scene/loaded_scene.h"

#include <cstdint>
#include <string>
#include <vector>

namespace osd_cull::plan {

/// \brief One PlanInput of a scene, with its planner key ("view/instance").
struct ScenePlanInput {
  std::string key;
  size_t view = 0;
  size_t instance = 0;
  PlanInput input;
};

/// \brief Every (view, instance) of `scene` at frame `frame` drawn with uniform `tess`:
/// deforming meshes count as moving (their cage is re-posed every frame); a mesh can be
/// hidden when the scene has occluders or another instance.
std::vector<ScenePlanInput> scenePlanInputs(const scene::LoadedScene& scene, uint32_t frame,
                                            double tess);

}  // namespace osd_cull::plan
