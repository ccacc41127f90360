#include "support/load_errors.h"

#include "adapters/load_mesh.h"
#include "osd_cull/error.h"

#include <gtest/gtest.h>

namespace osd_cull::test {

std::string loadError(const std::filesystem::path& file) {
  try {
    if (adapters::isBezierPatchFile(file))
      adapters::loadBezierPatches(file);
    else
      adapters::loadCage(file);
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type for " << file << ": " << e.what();
    return {};
  }
  ADD_FAILURE() << "no error for " << file;
  return {};
}

void expectLoadError(const std::filesystem::path& file, int line,
                     std::initializer_list<const char*> phrases) {
  const std::string message = loadError(file);
  const std::string prefix = file.string() + (line > 0 ? ":" + std::to_string(line) + ":" : ":");
  EXPECT_TRUE(message.starts_with(prefix)) << "expected prefix '" << prefix << "' in: " << message;
  for (const char* p : phrases)
    EXPECT_NE(message.find(p), std::string::npos) << "'" << p << "' not in: " << message;
}

}  // namespace osd_cull::test
