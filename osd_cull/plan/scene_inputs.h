#pragma once
/// \file scene_inputs.h
/// \brief The plan inputs of a loaded scene at one frame: one PlanInput per view and
/// instance, with the instance's model matrix, its posed bounds and the view's camera as the
/// ScenePlayer places them (scene_eval.h), so a plan can be made and printed without a
/// device, and `osd-cull plan SCENE` agrees with what `render SCENE` applies.

#include "osd_cull/plan/planner.h"
#include "osd_cull/scene/loaded_scene.h"

#include <cstdint>
#include <span>
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

/// \brief The planner key of (view, instance): "VIEW/INSTANCE-INDEX".
std::string scenePlanKey(const scene::LoadedScene& scene, size_t view, size_t instance);

/// \brief Object bounds of instance `instance`'s control points at scene time `seconds`:
/// the rest bounds of a static mesh; a deforming mesh's cage posed at the instance's time
/// (seconds + its offset, recentred) through its patch point matrix, in double, as the
/// ScenePlayer poses it.
frame::Bounds posedBounds(const scene::LoadedScene& scene, size_t instance, double seconds);

/// \brief Instance `instance` placed by `models[instance]` with object bounds
/// `objectBounds[instance]` in view `view` seen by `camera`: its patch counts, `tess`,
/// whether it deforms and its cage moved this frame (`cageMoved`), whether it is displaced,
/// and occluders = the scene has triangle occluders or another instance whose box is not
/// outside the view (selfOccluding is left to the caller: selfOccluding()).
PlanInput instancePlanInput(const scene::LoadedScene& scene, size_t view, size_t instance,
                            std::span<const frame::Bounds> objectBounds,
                            std::span<const glm::dmat4> models, const frame::Camera& camera,
                            double tess, bool cageMoved);

/// \brief Per instance, whether its mesh can hide parts of itself (PlanInput::
/// selfOccluding): a deforming mesh can (its pose is not its rest shape), a static one as
/// mayHideItself() finds its patches. Computed once per mesh.
std::vector<bool> selfOccluding(const scene::LoadedScene& scene);

/// \brief Every (view, instance) of `scene` at frame `frame` drawn with uniform `tess`:
/// deforming meshes count as moving (their cage is posed at the frame, as the first frame
/// a ScenePlayer renders poses it).
std::vector<ScenePlanInput> scenePlanInputs(const scene::LoadedScene& scene, uint32_t frame,
                                            double tess);

}  // namespace osd_cull::plan
