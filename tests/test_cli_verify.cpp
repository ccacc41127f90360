// `osd-cull verify`'s report: a legend under each table, one line per skip reason, and a
// last line PASS or FAIL: <reason> that agrees with the exit status (verify_report.h).
#include "support/run_command.h"
#include "support/test_data.h"
#include "verify_report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace osd_cull {
namespace {

using test::runCommand;

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// The last non-empty line of `text`.
std::string lastLine(std::string text) {
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text.substr(text.rfind('\n') + 1);
}

TEST(VerifyReport, PassingRunExplainsEveryColumnAndEndsWithPass) {
  if (!std::filesystem::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  const auto r = runCommand(test::osdCullProgram().string() +
                            " verify --views 2 --width 48 --height 48 --methods frustum,tcone,hiz "
                            "--sample 2 2>/dev/null");
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  for (const char* column :
       {"  cull%  ", "  ref-cull%  ", "  agree%  ", "  !in-ref  ", "  oracle-inv%  ", "  false  ",
        "  ns/patch  ", "  drawn%  ", "  false-pixels  ", "  sample-viol  ", "  pixels-lost  "})
    EXPECT_EQ(occurrences(r.output, std::string("\n") + column), 1u) << column << "\n" << r.output;
  EXPECT_NE(r.output.find("GPU culls the reference does not make (must be 0)"), std::string::npos);
  EXPECT_EQ(lastLine(r.output), "PASS") << r.output;
}

TEST(VerifyReport, DisplacedMeshSaysWhyBackPatchMethodsAreSkippedOnce) {
  if (!std::filesystem::exists(test::osdCullProgram())) GTEST_SKIP() << "osd-cull not built";
  OSD_CULL_REQUIRE_DATA();
  const auto r =
      runCommand(test::osdCullProgram().string() + " verify " +
                 (test::dataDir() / "shapes/catmark_single_crease.obj").string() +
                 " --displacement procedural --views 1 --width 32 --height 32 2>/dev/null");
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  EXPECT_EQ(occurrences(r.output, "its normals are not the patch's normals"), 1u) << r.output;
  EXPECT_EQ(occurrences(r.output, "skipped "), 1u) << r.output;
  EXPECT_NE(r.output.find("skipped tcone, ncone, tangent-plane, tangent-plane-16, tcone-fp64, "
                          "ncone-fp64: back-patch culling is off (above)"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(lastLine(r.output), "PASS") << r.output;
}

frame::MethodTotals totals(const char* name, frame::CullStage stage) {
  frame::MethodTotals t;
  t.name = name;
  t.stage = stage;
  return t;
}

TEST(VerifyReport, FalseCullsAndCullsOutsideTheReferenceFailWithTheirCounts) {
  std::vector<frame::MethodTotals> all = {totals("frustum", frame::CullStage::Frustum),
                                          totals("tcone", frame::CullStage::BackPatch),
                                          totals("hiz", frame::CullStage::Occlusion)};
  cli::VerifyVerdict v = cli::judgeVerify(all, false);
  EXPECT_TRUE(v.ok && v.okButSilhouettes);
  EXPECT_EQ(cli::verdictLine(v), "PASS");

  all[1].falseCulls = 3;
  all[1].falseCullPixels = 7;
  all[2].notInReference = 2;
  v = cli::judgeVerify(all, false);
  EXPECT_FALSE(v.ok || v.okButSilhouettes);
  EXPECT_EQ(cli::verdictLine(v),
            "FAIL: tcone: 3 false culls; hiz: 2 culls outside the double reference");
  EXPECT_EQ(cli::finishVerify(v, 0), 1);
  EXPECT_EQ(cli::finishVerify(cli::judgeVerify({}, false), 0), 0);
  EXPECT_EQ(cli::finishVerify(cli::judgeVerify({}, false), 4), 1);  // validation messages
}

TEST(VerifyReport, SilhouettePixelsOfSurfaceExactBackPatchCullsPassButAreNotOk) {
  std::vector<frame::MethodTotals> all = {totals("tcone", frame::CullStage::BackPatch)};
  all[0].falseCulls = 2;
  all[0].falseCullPixels = 2;  // one pixel each: silhouette chords
  const cli::VerifyVerdict exact = cli::judgeVerify(all, true);
  EXPECT_FALSE(exact.ok);
  EXPECT_TRUE(exact.okButSilhouettes);
  EXPECT_EQ(cli::verdictLine(exact), "PASS");
  EXPECT_EQ(cli::verdictLine(cli::judgeVerify(all, false)), "FAIL: tcone: 2 false culls");
}

}  // namespace
}  // namespace osd_cull
