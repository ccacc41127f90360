// Registrations of the parametric tangent-plane back-patch test (Loop, Niessner, Eisenacher):
// one thread per patch (shaders/cull/tangent_plane.glsl: the factored form of
// tangent_plane_factored.glsl, no table) and 16 threads per patch
// (shaders/cull/tangent_plane_16.glsl, the section 6 table order). The index and weight
// table is derived from its definition by bound::tangentPlaneTerms() and uploaded, never
// typed in. (As GLSL constants, bound::tangentPlaneTableGlsl(), the kernel takes lavapipe's
// LLVM backend 150-190 s to compile; from a buffer 0.4 s.)
#include "osd_cull/bound/tangent_plane_table.h"
#include "osd_cull/frame/cull/cull_methods.h"
#include "osd_cull/frame/cull/tangent_plane_factored_glsl.h"

#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>

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

// W = max over the 64 targets of Σ |w| over its terms, rounded up to float: the factored
// kernel bounds the reference's margin base m_i <= 6 W C^3 with it.
std::string weightBoundGlsl() {
  double sums[64] = {};
  for (const bound::TangentPlaneTerm& t : bound::tangentPlaneTerms())
    sums[t.target] += std::abs(t.weight);
  double w = 0.0;
  for (double s : sums) w = std::max(w, s);
  const float up = std::nextafter(static_cast<float>(w), std::numeric_limits<float>::infinity());
  char text[96];
  std::snprintf(text, sizeof text, "const float kTangentPlaneWeightBound = %.9g;\n", double(up));
  return text;
}

}  // namespace

CullMethod tangentPlaneCullMethod() {
  CullMethod m;
  m.name = "tangent-plane";
  m.stage = CullStage::BackPatch;
  m.summary =
      "parametric tangent plane, 64 control planes by the factored form, 1 thread per patch";
  m.glslFile = "cull/tangent_plane.glsl";
  m.generatedGlsl = [] {
    // The generated function as a one-line macro, expanded by tangent_plane_factored.glsl
    // after the helpers it calls.
    std::string body = tangentPlaneFactoredGlsl(), macro = "#define TANGENT_PLANE_FACTORED_SIGNS ";
    for (char ch : body) macro += ch == '\n' ? ' ' : ch;
    return weightBoundGlsl() + macro + "\n";
  };
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
