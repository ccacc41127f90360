// bench-cull as the accuracy-versus-time study runs it (scripts/study.sh,
// docs/results/accuracy-vs-time.md): its Hi-Z and displaced kernels cull what `osd-cull
// verify` culls on the same views, each frame mode is compared with its own unculled
// frame, the break-even sweep draws counted shares and reads its crossing off its own
// fit, and bad mode names are named. Small images and few views: values, not timings.
#include "support/run_command.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

namespace fs = std::filesystem;

using test::runCommand;

fs::path benchProgram() { return fs::path(OSD_CULL_BINARY_DIR) / "benchmarks" / "bench-cull"; }

std::string bigguy() { return (test::dataDir() / "characters" / "bigguy.obj").string(); }

// The same views for both programs: sphere views, seed 1, at this size and level.
const std::string kViews = " --levels 1 --width 160 --height 120 --repeats 1";
const std::string kVerifyViews =
    " --level 1 --width 160 --height 120 --seed 1 --view-set sphere --views 3 --tess 4";
const std::string kDisplacement = " --displacement procedural --displacement-scale 0.64";

/// The rows of the Markdown tables in `text` with `cells` cells, the first a number.
std::vector<std::vector<std::string>> tableRows(const std::string& text, size_t cells) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.size() < 2 || line[0] != '|') continue;
    std::vector<std::string> row;
    std::istringstream cellsIn(line.substr(1));
    for (std::string cell; std::getline(cellsIn, cell, '|');) {
      const size_t a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
      row.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
    }
    if (row.size() == cells && !row[0].empty() && std::isdigit(row[0][0])) rows.push_back(row);
  }
  return rows;
}

double number(const std::string& cell) { return std::stod(cell); }  // "12.5%" reads 12.5

/// verify's cull rate (%) of `method`.
double verifyRate(const std::string& method, const std::string& args, const fs::path& json) {
  const auto r = runCommand(test::osdCullProgram().string() + " verify " + bigguy() + kVerifyViews +
                            " --validate " + args + " --json " + json.string());
  EXPECT_TRUE(fs::exists(json)) << r.output;
  std::ifstream in(json);
  const nlohmann::json doc = nlohmann::json::parse(in);
  for (const auto& m : doc["methods"])
    if (m["name"] == method) return 100.0 * m["cull_rate"].get<double>();
  ADD_FAILURE() << "verify ran no " << method << ":\n" << r.output;
  return -1.0;
}

bool ready() {
  return fs::exists(benchProgram()) && fs::exists(test::osdCullProgram()) && test::haveData();
}

TEST(BenchCullStudy, KernelCullRatesEqualVerifysOnTheSameViews) {
  if (!ready()) GTEST_SKIP() << "bench-cull, osd-cull or the shared data missing";
  const fs::path dir = fs::path(OSD_CULL_BINARY_DIR) / "test_output" / "bench_cull_study";
  fs::create_directories(dir);
  const auto r = runCommand(benchProgram().string() + " --validate --parts 1 --mesh " + bigguy() +
                            kViews + " --views 3 --kernel-tess 4" + kDisplacement +
                            " --methods tcone,tcone/listed,hiz,hiz/full-tight,acon-caf,con-oobb");
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  std::map<std::string, double> bench;
  for (const auto& row : tableRows(r.output, 8)) bench[row[3]] = number(row[4]);
  ASSERT_EQ(bench.size(), 6u) << r.output;
  const std::map<std::string, std::string> verifyArgs = {
      {"tcone", "--methods tcone"},
      {"tcone/listed", "--methods tcone --drawn-enumerate"},
      {"hiz", "--methods hiz"},
      {"hiz/full-tight", "--methods hiz --hiz-full --hiz-tight"},
      {"acon-caf", kDisplacement + " --displaced-bound acon --displaced-box caf"},
      {"con-oobb", kDisplacement + " --displaced-bound con --displaced-box oobb"}};
  for (const auto& [name, args] : verifyArgs) {
    std::string file = name;
    std::replace(file.begin(), file.end(), '/', '-');
    const double rate = verifyRate(name.substr(0, name.find('/')), args, dir / (file + ".json"));
    EXPECT_GT(rate, 0.0) << name;
    EXPECT_NEAR(bench.at(name), rate, 0.051) << name << ": bench-cull against verify";
  }
}

TEST(BenchCullStudy, FrameModesAreComparedWithTheirOwnUnculledFrame) {
  if (!ready()) GTEST_SKIP() << "bench-cull, osd-cull or the shared data missing";
  const auto r =
      runCommand(benchProgram().string() + " --validate --parts 2 --mesh " + bigguy() + kViews +
                 " --views 2 --tess 2" + kDisplacement + " --frame-modes tcone,hiz/full,acon-caf");
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  std::map<std::string, std::vector<std::string>> rows;
  for (const auto& row : tableRows(r.output, 6)) rows[row[1]] = row;
  ASSERT_EQ(rows.size(), 5u) << r.output;  // none, tcone, hiz/full, displaced:none, acon-caf
  const double n = number(rows.at("none")[2]);
  EXPECT_EQ(number(rows.at("displaced:none")[2]), n);
  EXPECT_EQ(number(rows.at("none")[5]), 1.0);
  EXPECT_EQ(number(rows.at("displaced:none")[5]), 1.0);
  // Every patch tessellated at level 2: at least (2 + 1)^2 evaluations each.
  EXPECT_GE(number(rows.at("none")[3]), 9.0 * n);
  for (const std::string mode : {"tcone", "hiz/full", "acon-caf"}) {
    const auto& row = rows.at(mode);
    EXPECT_LT(number(row[2]), n) << mode << " culls";
    EXPECT_LT(number(row[3]), number(rows.at("none")[3])) << mode << " evaluates less";
    // The ratio is to the unculled frame of the same mesh (displaced or not).
    const std::string base = mode == "acon-caf" ? "displaced:none" : "none";
    EXPECT_NEAR(number(row[5]), number(row[4]) / number(rows.at(base)[4]), 0.011) << mode;
  }
}

TEST(BenchCullStudy, BreakEvenSweepDrawsCountedSharesAndReadsItsOwnFit) {
  if (!ready()) GTEST_SKIP() << "bench-cull, osd-cull or the shared data missing";
  const auto r = runCommand(benchProgram().string() + " --validate --parts 3 --mesh " + bigguy() +
                            kViews + " --break-even-tess 2 --break-even-views 1" +
                            " --break-even-methods frustum,tcone");
  ASSERT_EQ(r.exitCode(), 0) << r.output;
  std::vector<std::pair<double, double>> sweep;  // (share, ratio) by increasing zoom
  double tconeShare = -1.0;
  std::map<std::string, std::vector<double>> summary;  // method -> a, b, x*
  for (const auto& row : tableRows(r.output, 6)) {
    if (row[5].ends_with("%"))
      summary[row[1]] = {number(row[3]), number(row[4]), number(row[5])};
    else if (row[1] == "tcone")
      tconeShare = number(row[3]);
    else if (row[1] == "frustum" && sweep.size() < 6)
      sweep.push_back({number(row[3]), number(row[4])});
  }
  ASSERT_EQ(sweep.size(), 6u) << r.output;
  ASSERT_EQ(summary.size(), 3u) << r.output;  // the sweep, frustum, tcone
  // Zoom 1 keeps the framed mesh; each narrower frustum draws no more; zoom 1000 nothing.
  EXPECT_GT(sweep.front().first, 0.9);
  for (size_t i = 1; i < sweep.size(); ++i) EXPECT_LE(sweep[i].first, sweep[i - 1].first);
  EXPECT_LT(sweep.back().first, 0.01);
  EXPECT_GT(tconeShare, 0.0);
  EXPECT_LT(tconeShare, 1.0) << "the back-patch stage culls some patches";
  // The fit is the least-squares line through the printed medians ...
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [x, y] : sweep) {
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double b = (6 * sxy - sx * sy) / (6 * sxx - sx * sx), a = (sy - b * sx) / 6;
  const auto& fit = summary.at("frustum sweep");
  EXPECT_NEAR(fit[0], a, 0.003);
  EXPECT_NEAR(fit[1], b, 0.003);
  // ... and each break-even is its crossing with the unculled frame: (a + b - 1) / b.
  for (const auto& [method, v] : summary) {
    EXPECT_EQ(v[1], fit[1]) << method << " uses the sweep's slope";
    EXPECT_NEAR(v[2], 100.0 * (v[0] + v[1] - 1.0) / v[1], 0.1 + 0.1 / std::abs(v[1])) << method;
  }
}

TEST(BenchCullStudy, BadModeNamesAreNamed) {
  if (!ready()) GTEST_SKIP() << "bench-cull, osd-cull or the shared data missing";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--parts 1 --methods hiz/bogus", "'hiz/bogus': Hi-Z options are /full, /tight, /full-tight"},
      {"--parts 1 --methods tcone/exact",
       "'tcone/exact': the back-patch options are /surface and /listed"},
      {"--parts 1 --methods acon-caf", "'acon-caf' is a displaced kernel: give --displacement"},
      {"--parts 1 --methods blah", "unknown cull method 'blah'"},
      {"--parts 2 --frame-modes tcone,frustum/listed", "'frustum/listed': frustum takes no option"},
      {"--parts 3 --break-even-methods hiz", "'hiz': the break-even methods are frustum and"}};
  for (const auto& [args, message] : cases) {
    const auto r =
        runCommand(benchProgram().string() + " --mesh " + bigguy() + kViews + " --views 1 " + args);
    EXPECT_EQ(r.exitCode(), 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
  }
}

}  // namespace
}  // namespace osd_cull
