#include "osd_cull/scene/default_scene.h"

#include "osd_cull/scene/demo_shapes.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/procedural.h"

#include <algorithm>

namespace osd_cull::scene {

namespace {

PatchSet extract(CageMesh cage, const PatchOptions& options, const glm::dvec3& offset,
                 double size) {
  scale(cage, size);
  translate(cage, offset);
  return extractPatches(cage, options).patches;
}

}  // namespace

Scene defaultScene(const PatchOptions& options) {
  Scene s;
  s.patches = extract(defaultMesh(), options, {0.0, 0.0, 0.0}, 1.0);
  s.patches = scene::concatenate(s.patches,
                                 extract(torus(12, 8, 1.0, 0.4), options, {2.6, 0.6, -0.6}, 1.0));
  s.patches = scene::concatenate(s.patches, extract(poleSphere(5), options, {-1.3, 2.8, 0.0}, 1.0));
  s.patches = scene::concatenate(s.patches, extract(creasedCube(), options, {1.0, 2.4, -0.4}, 0.6));
  s.patches.source = "built-in:scene (default mesh, torus, pole sphere, creased cube, wall)";
  s.occluders.push_back(frame::boxMesh({-2.5, 1.45, -1.0}, {-0.2, 1.55, 0.8}));
  s.occluders.push_back(frame::boxMesh({-3.5, -2.5, -1.15}, {4.2, 4.5, -1.0}));
  return s;
}

SceneDescription defaultSceneDescription(uint32_t frames) {
  SceneDescription d;
  d.source = "built-in:scene";
  auto mesh = [&](const std::string& name, const std::string& builtIn) {
    MeshDescription m;
    m.name = name;
    m.builtIn = builtIn;
    d.meshes.push_back(m);
  };
  mesh("default", "default");
  mesh("torus", "torus");
  mesh("pole-sphere", "pole-sphere-5");
  mesh("creased-cube", "creased-cube");
  mesh("character", "character");
  // Arms and legs swing (the skinning deformer's limb rig): a walk on the spot.
  d.meshes.back().animation.kind = AnimationSource::Kind::Skin;
  d.meshes.back().animation.skinning.rig = SkinningRig::Limbs;
  d.meshes.back().animation.skinning.swingDegrees = 35.0;
  d.meshes.back().animation.skinning.frequency = 1.0;
  auto instance = [&](size_t m, const glm::dvec3& at, double size) {
    InstanceDescription i;
    i.name = d.meshes[m].name;
    i.mesh = m;
    i.transform = composeTransform(at, glm::dvec3(0.0), glm::dvec3(size));
    d.instances.push_back(i);
  };
  instance(0, {0.0, 0.0, 0.0}, 1.0);
  instance(1, {2.6, 0.6, -0.6}, 1.0);
  instance(2, {-1.3, 2.8, 0.0}, 1.0);
  instance(3, {1.0, 2.4, -0.4}, 0.6);
  // The character stands on the ground slab (top z = -1) in front of the wall, turned
  // towards the first camera position.
  InstanceDescription figure;
  figure.name = "character";
  figure.mesh = 4;
  figure.transform = composeTransform({-1.6, -0.9, -1.0}, {0.0, 0.0, -20.0}, glm::dvec3(0.75));
  d.instances.push_back(figure);
  OccluderDescription wall, ground;
  wall.boxMin = {-2.5, 1.45, -1.0};
  wall.boxMax = {-0.2, 1.55, 0.8};
  ground.boxMin = {-3.5, -2.5, -1.15};
  ground.boxMax = {4.2, 4.5, -1.0};
  d.occluders = {wall, ground};
  // The camera swings from the default direction around to behind the wall and closes in.
  ViewDescription main;
  main.name = "main";
  main.target = {0.4, 1.2, -0.2};
  main.up = {0.0, 0.0, 1.0};
  const double seconds = std::max(1.0, double(frames) / 24.0);
  main.keys = {{0.0, {3.6, -5.5, 3.3}, main.target},
               {0.5 * seconds, {-4.5, -4.2, 2.4}, main.target},
               {seconds, {-3.4, 1.0, 1.1}, {0.8, 2.2, -0.2}}};
  main.eye = main.keys.front().eye;
  d.views.push_back(main);
  d.settings.frameCount = frames;
  return d;
}

LoadedScene builtInScene(uint32_t frames) {
  LoadedScene s;
  s.description = defaultSceneDescription(frames);
  for (const MeshDescription& m : s.description.meshes) {
    CageMesh cage = *builtInMesh(m.builtIn);
    auto animation = makeProceduralAnimation(m.animation, cage.positions);
    s.meshes.push_back(
        makeSceneMesh(m.name, std::move(cage), m.patches, m.recentre, std::move(animation)));
  }
  for (const OccluderDescription& o : s.description.occluders)
    s.occluders.push_back(frame::boxMesh(o.boxMin, o.boxMax));
  return s;
}

}  // namespace osd_cull::scene
