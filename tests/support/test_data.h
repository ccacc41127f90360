#pragma once
/// \file test_data.h
/// \brief Where tests find ../shared/data, and a skip when it is absent.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace osd_cull::test {

/// \brief The shared data folder: $OSD_CULL_DATA_DIR, else <project root>/../shared/data.
std::filesystem::path dataDir();

/// \brief True when dataDir() exists.
bool haveData();

/// \brief Every Catmull-Clark OBJ shape in data/shapes (sorted), empty if no data.
std::vector<std::filesystem::path> catmarkShapes();

}  // namespace osd_cull::test

/// Skips the current test with a clear message when ../shared/data is absent.
#define OSD_CULL_REQUIRE_DATA()                                                        \
  do {                                                                                 \
    if (!::osd_cull::test::haveData())                                                 \
      GTEST_SKIP() << "shared data folder not found at " << ::osd_cull::test::dataDir() \
                   << " (set OSD_CULL_DATA_DIR)";                                      \
  } while (0)
