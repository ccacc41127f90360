// Registrations of the cone-of-normals back-patch tests (shaders/cull/cone.glsl): the same
// kernel, different cones. Both are built on the host in double once per static mesh
// (bound::buildPatchCones) and uploaded; Gregory patches carry the Gregory TCONE.
#include "osd_cull/frame/cull/cull_methods.h"

namespace osd_cull::frame {

CullMethod tconeCullMethod() {
  CullMethod m;
  m.name = "tcone";
  m.stage = CullStage::BackPatch;
  m.summary = "cone of normals from tangent and bitangent cones (Sederberg-Meyers), per mesh";
  m.glslFile = "cull/cone.glsl";
  m.reference = bound::BackPatchMethod::TCone;
  return m;
}

CullMethod nconeCullMethod() {
  CullMethod m;
  m.name = "ncone";
  m.stage = CullStage::BackPatch;
  m.summary = "cone of the normal patch Bu x Bv (Shirman-Abi-Ezzi), per mesh";
  m.glslFile = "cull/cone.glsl";
  m.reference = bound::BackPatchMethod::NCone;
  return m;
}

namespace {

// The fp64 kernel of a cone method (shaders/cull/cone_fp64.glsl): the same cones, the
// cull-region test in double.
CullMethod fp64Variant(CullMethod m) {
  m.summary = m.name + " with the cull-region test in double (shaderFloat64)";
  m.name += "-fp64";
  m.glslFile = "cull/cone_fp64.glsl";
  m.needsFloat64 = true;
  return m;
}

}  // namespace

CullMethod tconeFp64CullMethod() { return fp64Variant(tconeCullMethod()); }

CullMethod nconeFp64CullMethod() { return fp64Variant(nconeCullMethod()); }

}  // namespace osd_cull::frame
