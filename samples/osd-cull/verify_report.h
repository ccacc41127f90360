#pragma once
/// \file verify_report.h
/// \brief The tables and JSON of `osd-cull verify`, shared by the mesh and the scene forms.

#include "osd_cull/frame/verify/cull_verification.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace osd_cull::cli {

/// \brief Whether a run passed: `ok` with no violation at all; `okButSilhouettes` also when
/// the only false culls are --surface-exact silhouette chords (reported, not failed).
/// `failures` names each violation that fails the run ("tcone: 3 false culls"), so it is
/// empty exactly when `okButSilhouettes`.
struct VerifyVerdict {
  bool ok = true;
  bool okButSilhouettes = true;
  std::vector<std::string> failures;
};

/// \brief Judges the totals: a GPU cull outside the double-precision reference, a false
/// cull (a culled patch with oracle pixels; with `surfaceExact`, back-patch culls whose
/// every false pixel is a single silhouette pixel are exempt), a visible sample or a lost
/// pixel fails the run.
VerifyVerdict judgeVerify(std::span<const frame::MethodTotals> totals, bool surfaceExact);

/// \brief The run's last line: "PASS" or "FAIL: <the failures, '; '-separated>".
std::string verdictLine(const VerifyVerdict& verdict);

/// \brief Prints verdictLine() for `verdict`, or a FAIL line for the validation layers'
/// messages, and returns the exit status (0 pass, 1 fail).
int finishVerify(const VerifyVerdict& verdict, uint64_t validationMessages);

/// \brief Prints "skipped A, B: reason" once per distinct reason, in the order given; a
/// reason ending in ": " + `saidAbove` (non-empty: a text the header printed already)
/// ends in " (above)" instead.
void printSkipped(std::span<const std::pair<std::string, std::string>> skipped,
                  const std::string& saidAbove = {});

/// \brief Prints the per-method table (rates, reference agreement, oracle, false culls,
/// ns/patch), the false-cull list, and with `detail` the sampling/image table, each with
/// a legend of its columns; returns judgeVerify().
VerifyVerdict printVerifyTables(std::span<const frame::MethodTotals> totals, uint32_t patchCount,
                                bool oracle, bool surfaceExact, bool detail);

/// \brief The JSON object of one method's totals.
nlohmann::ordered_json methodJson(const frame::MethodTotals& t, uint32_t patchCount, bool oracle);

/// \brief Adds `b`'s counts to `a` (same method), e.g. over the instances and frames of a
/// scene; the false-cull list keeps its first 64 entries.
void accumulate(frame::MethodTotals& a, const frame::MethodTotals& b);

/// \brief Ends a verify run's JSON `out` with the methods skipped and the verdict, writes
/// it to `path` and says so on stdout.
/// \throws osd_cull::Error when the file cannot be written.
void finishVerifyJson(nlohmann::ordered_json out,
                      std::span<const std::pair<std::string, std::string>> skipped,
                      const VerifyVerdict& verdict, const std::string& path);

}  // namespace osd_cull::cli
