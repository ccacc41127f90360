#include "support/cull_test_meshes.h"

#include "adapters/load_mesh.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"

#include <gtest/gtest.h>

namespace osd_cull::test {

CullMesh loadCullMesh(const std::filesystem::path& path, int level) {
  CullMesh m;
  m.name = path.filename().string();
  PatchOptions options;
  options.isolationLevel = level;
  bound::CullablePatches c = bound::cullablePatches(adapters::loadCage(path), options);
  m.validity = std::move(c.backPatch);
  m.patches = std::move(c.extraction.patches);
  return m;
}

void expectNoViolations(const frame::CullVerifier& verifier, const std::string& context) {
  for (const frame::MethodTotals& t : verifier.totals()) {
    const std::string what = context + " " + t.name;
    EXPECT_EQ(t.notInReference, 0u) << what << ": GPU culls the reference keeps";
    EXPECT_EQ(t.samplingViolations, 0u) << what << ": culled patches with visible samples";
    EXPECT_EQ(t.pixelsLost, 0u) << what << ": pixels lost by culling";
    EXPECT_EQ(t.falseCulls, 0u) << what << ": culled patches with pixels";
  }
}

const frame::MethodTotals& totalsOf(const frame::CullVerifier& verifier, const std::string& name) {
  for (const frame::MethodTotals& t : verifier.totals())
    if (t.name == name) return t;
  ADD_FAILURE() << "no totals for method " << name;
  static const frame::MethodTotals none;
  return none;
}

}  // namespace osd_cull::test
