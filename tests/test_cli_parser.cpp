// The osd-cull command line (CLI11): exit status 2 for usage errors, one line per option in
// --help, outputs checked before any work, lists and choices checked, --version.
#include "osd_cull/version.h"
#include "support/run_command.h"
#include "support/temp_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <set>
#include <string>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;
using test::runCommand;

#define REQUIRE_PROGRAM() \
  if (!fs::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built"

test::CommandResult osdCull(const std::string& arguments) {
  return runCommand(test::osdCullProgram().string() + " " + arguments);
}

TEST(CommandLine, UsageErrorsExitWithStatusTwoAndNameTheOption) {
  REQUIRE_PROGRAM();
  struct Case {
    std::string args;
    std::string expected;
  };
  const Case cases[] = {
      {"", "Usage"},
      {"frobnicate", "unknown command 'frobnicate'"},
      {"info --level 11", "--level: 11 is out of range [0, 10]"},
      {"info --level two", "'two' is not an integer"},
      {"info --frobnicate 1", "unknown option --frobnicate"},
      {"info --frobnicate", "unknown option --frobnicate"},  // last on the line
      {"info --json --frobnicate=3", "unknown option --frobnicate"},
      {"info a.obj b.obj", "at most one MESH"},
      {"info --level", "--level"},
      {"render --width 64", "--out"},
      {"render --out x.png --tess 3 --adaptive 4", "exclude"},
      {"render --out x.png --aggressive", "need --cull"},
      {"verify --methods ,", "--methods: ',' names nothing"},
      {"verify --methods frustum,,hiz", "has an empty item"},
      {"verify --methods frustum,bogus", "'bogus' is not one of"},
  };
  for (const Case& c : cases) {
    const auto r = osdCull(c.args);
    EXPECT_EQ(r.exitCode(), 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.args << "\n" << r.output;
  }
}

TEST(CommandLine, BackPatchMethodErrorListsOnlyBackPatchMethods) {
  REQUIRE_PROGRAM();
  const auto r = osdCull("render --out x.png --cull backpatch --backpatch-method bogus");
  EXPECT_EQ(r.exitCode(), 2) << r.output;
  const auto line = r.output.substr(0, r.output.find('\n'));
  EXPECT_NE(line.find("'bogus' is not a back-patch method: one of"), std::string::npos) << line;
  EXPECT_NE(line.find("tangent-plane"), std::string::npos) << line;
  EXPECT_NE(line.find("tcone"), std::string::npos) << line;
  EXPECT_EQ(line.find("frustum"), std::string::npos) << line;
  EXPECT_EQ(line.find("hiz"), std::string::npos) << line;
}

TEST(CommandLine, HelpListsEveryOptionOnceAndExitsZero) {
  REQUIRE_PROGRAM();
  for (const char* command : {"info", "render", "verify", "view"}) {
    const auto r = osdCull(std::string(command) + " --help");
    ASSERT_EQ(r.exitCode(), 0) << command << "\n" << r.output;
    std::multiset<std::string> options;
    const std::regex declared(R"(\n  (--[a-z0-9-]+))");
    for (auto it = std::sregex_iterator(r.output.begin(), r.output.end(), declared);
         it != std::sregex_iterator(); ++it)
      options.insert((*it)[1]);
    EXPECT_GT(options.size(), 3u) << r.output;
    for (const auto& o : options) EXPECT_EQ(options.count(o), 1u) << command << ": " << o;
  }
  const auto render = osdCull("render --help").output;
  for (const char* o : {"--level", "--scheme", "--cull", "--device", "--out", "--stats"})
    EXPECT_NE(render.find(std::string("  ") + o), std::string::npos) << o << "\n" << render;
  EXPECT_EQ(osdCull("--help").exitCode(), 0);
}

/// The help text with every run of white space (line breaks and the indent of the
/// description column) as one space, so that a phrase may span lines.
std::string flatHelp(const std::string& command) {
  const auto r = osdCull(command + " --help");
  EXPECT_EQ(r.exitCode(), 0) << command << "\n" << r.output;
  return std::regex_replace(r.output, std::regex(R"(\s+)"), " ");
}

TEST(CommandLine, HelpStatesTheDefaultsAndTheAcceptedValues) {
  REQUIRE_PROGRAM();
  for (const char* command : {"render", "verify", "plan", "view", "info", "calibrate"}) {
    const std::string help = flatHelp(command);
    SCOPED_TRACE(command);
    EXPECT_EQ(help.find("none (default)"), std::string::npos) << help;
    EXPECT_EQ(help.find("else lavapipe"), std::string::npos) << help;
    EXPECT_EQ(help.find("1e+30"), std::string::npos) << help;
    EXPECT_FALSE(std::regex_search(help, std::regex(R"(:[A-Z]+ in \[)"))) << help;  // CLI::Range
    if (std::string(command) != "info") {
      EXPECT_NE(help.find("else the first discrete GPU, then integrated, then virtual, then CPU"),
                std::string::npos)
          << help;
    }
  }
  const std::string render = flatHelp("render"), verify = flatHelp("verify");
  EXPECT_NE(render.find("default: the effect plan chooses (--plan)"), std::string::npos);
  EXPECT_NE(flatHelp("view").find("(default: the effect plan chooses"), std::string::npos);
  for (const std::string& help : {render, verify}) {
    EXPECT_NE(help.find("--displacement-scale S:FLOAT scale, a finite number"), std::string::npos)
        << help;
    EXPECT_NE(help.find("--displacement-midlevel M:FLOAT midlevel"), std::string::npos) << help;
    EXPECT_NE(help.find("--displacement-lod L coarsest mip level the draw samples, 0 to 15"),
              std::string::npos)
        << help;
  }
  EXPECT_NE(render.find("--displaced-bound B extension of the bound: full, acon (default), con "),
            std::string::npos)
      << render;
  EXPECT_NE(render.find("--displaced-box X box the extension is applied to: oobb, caf (default)"),
            std::string::npos)
      << render;
  EXPECT_NE(verify.find("full, acon (default), con, all (each)"), std::string::npos) << verify;
  EXPECT_NE(verify.find("oobb, caf, all (each); default caf, all with --displaced-bound all"),
            std::string::npos)
      << verify;
  // The side status view: 90 degrees for a mesh (cmd_render.cpp), 120 for a scene
  // (scene_render.cpp), both in the option's text.
  EXPECT_NE(render.find("FILE_status_side.png from 90 degrees around the up axis; a scene: only "
                        "DIR/<view>_status_NNNN.png (needs --out-dir), seen from 120 degrees"),
            std::string::npos)
      << render;
}

TEST(CommandLine, AbsurdDisplacementNumbersAreRefusedWithTheRange) {
  REQUIRE_PROGRAM();
  auto r = osdCull("render --out x.png --displacement procedural --displacement-scale 1e31");
  EXPECT_EQ(r.exitCode(), 2) << r.output;
  EXPECT_NE(r.output.find("--displacement-scale: 1e31 is out of range [-1e+30, 1e+30]"),
            std::string::npos)
      << r.output;
  r = osdCull("render --out x.png --displacement procedural --displacement-midlevel nan");
  EXPECT_EQ(r.exitCode(), 2) << r.output;
  EXPECT_NE(r.output.find("--displacement-midlevel: 'nan' is not a finite number"),
            std::string::npos)
      << r.output;
  r = osdCull("render --out x.png --displacement procedural --displacement-lod 16");
  EXPECT_EQ(r.exitCode(), 2) << r.output;
  EXPECT_NE(r.output.find("--displacement-lod: 16 is out of range [0, 15]"), std::string::npos)
      << r.output;
}

TEST(CommandLine, OutputWeCannotWriteIsAnErrorBeforeRendering) {
  REQUIRE_PROGRAM();
  test::TempDir dir("osd_cull_cli_out_");
  auto r = osdCull("render --out " + (dir.path() / "image.jpg").string());
  EXPECT_EQ(r.exitCode(), 2) << r.output;
  EXPECT_NE(r.output.find("--out: cannot write"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(".png"), std::string::npos) << r.output;

  r = osdCull("render --out " + (dir.path() / "no" / "such" / "dir" / "image.png").string());
  EXPECT_EQ(r.exitCode(), 1) << r.output;
  EXPECT_NE(r.output.find("does not exist"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("device:"), std::string::npos) << "rendered first:\n" << r.output;

  // A directory that cannot be written (also for root: /proc refuses new files).
  r = osdCull("render --out /proc/osd_cull_image.png");
  EXPECT_EQ(r.exitCode(), 1) << r.output;
  EXPECT_NE(r.output.find("cannot write in directory '/proc'"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("device:"), std::string::npos) << "rendered first:\n" << r.output;

  const fs::path file = dir.write("plain_file", "x");
  r = osdCull("render --out x.png --out-dir " + file.string());
  EXPECT_EQ(r.exitCode(), 1) << r.output;
  EXPECT_NE(r.output.find("--out-dir"), std::string::npos) << r.output;

  r = osdCull("verify --views 1 --json " + (dir.path() / "results.txt").string());
  EXPECT_EQ(r.exitCode(), 2) << r.output;
  EXPECT_NE(r.output.find("--json: cannot write"), std::string::npos) << r.output;
  // The checks leave nothing behind: no image, no write probe.
  std::set<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir.path()))
    left.insert(entry.path().filename().string());
  EXPECT_EQ(left, std::set<std::string>{"plain_file"});
}

TEST(CommandLine, VersionMatchesTheLibraryHeader) {
  REQUIRE_PROGRAM();
  const auto r = osdCull("--version");
  EXPECT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_EQ(r.output.rfind(std::string("osd-cull ") + kVersion + " (OpenSubdiv 3.", 0), 0u)
      << r.output;
  EXPECT_STREQ(libraryVersion(), OSD_CULL_VERSION_STRING);
}

}  // namespace
}  // namespace osd_cull
