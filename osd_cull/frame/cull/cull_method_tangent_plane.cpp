// Registrations of the parametric tangent-plane back-patch test (Loop, Niessner, Eisenacher):
// one thread per patch (shaders/cull/tangent_plane.glsl, section 5 order) and 16 threads
// per patch (shaders/cull/tangent_plane_16.glsl, section 6 order). The index and weight
// table is derived from its definition by bound::tangentPlaneTerms() and uploaded, never
// typed in. (As GLSL constants, bound::tangentPlaneTableGlsl(), the kernel takes lavapipe's
// LLVM backend 150-190 s to compile; from a buffer 0.4 s.)
#include "osd_cull/bound/tangent_plane_table.h"
#include "osd_cull/frame/cull/cull_methods.h"

#include <bit>

namespace osd_cull::frame {

namespace {

// Two words per term: target | j << 8 | k << 16 | l << 24, and the weight's float bits
// (the exact rational weight rounded once to double, then to float).
std::vector<uint32_t> packTable(std::span<const bound::TangentPlaneTerm> terms) {
  std::vector<uint32_t> words;
  words.reserve(2 * terms.size());
  for (const bound::TangentPlaneTerm& t : terms) {
    words.push_back(t.target | (t.j << 8) | (t.k << 16) | (t.l << 24));
    words.push_back(std::bit_cast<uint32_t>(static_cast<float>(t.weight)));
  }
  return words;
}

std::string termCountGlsl(size_t count) {
  return "const uint kTangentPlaneTermCount = " + std::to_string(count) + "u;\n";
}

}  // namespace

CullMethod tangentPlaneCullMethod() {
  CullMethod m;
  m.name = "tangent-plane";
  m.stage = CullStage::BackPatch;
  m.summary = "parametric tangent plane, 64 clip-space control planes, 1 thread per patch";
  m.glslFile = "cull/tangent_plane.glsl";
  m.generatedGlsl = [] { return termCountGlsl(bound::tangentPlaneTerms().size()); };
  m.table = [] { return packTable(bound::tangentPlaneTerms()); };
  m.reference = bound::BackPatchMethod::TangentPlane;
  return m;
}

CullMethod tangentPlane16CullMethod() {
  CullMethod m;
  m.name = "tangent-plane-16";
  m.stage = CullStage::BackPatch;
  m.summary = "parametric tangent plane, 16 threads per patch (section 6)";
  m.glslFile = "cull/tangent_plane_16.glsl";
  m.lanesPerPatch = 16;
  m.generatedGlsl = [] { return termCountGlsl(bound::tangentPlaneParallelTerms().size()); };
  m.table = [] { return packTable(bound::tangentPlaneParallelTerms()); };
  m.reference = bound::BackPatchMethod::TangentPlane;
  return m;
}

}  // namespace osd_cull::frame
