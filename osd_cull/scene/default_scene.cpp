#include "osd_cull/scene/default_scene.h"

#include "osd_cull/frame/demo_shapes.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/scene/procedural.h"

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
  s.patches = frame::concatenate(s.patches,
                                 extract(torus(12, 8, 1.0, 0.4), options, {2.6, 0.6, -0.6}, 1.0));
  s.patches = frame::concatenate(s.patches, extract(poleSphere(5), options, {-1.3, 2.8, 0.0}, 1.0));
  s.patches = frame::concatenate(s.patches, extract(creasedCube(), options, {1.0, 2.4, -0.4}, 0.6));
  s.patches.source = "built-in:scene (default mesh, torus, pole sphere, creased cube, wall)";
  s.occluders.push_back(frame::boxMesh({-2.5, 1.45, -1.0}, {-0.2, 1.55, 0.8}));
  s.occluders.push_back(frame::boxMesh({-3.5, -2.5, -1.15}, {4.2, 4.5, -1.0}));
  return s;
}

}  // namespace osd_cull::scene
