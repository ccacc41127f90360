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
struct VerifyVerdict {
  bool ok = true;
  bool okButSilhouettes = true;
};

/// \brief Prints the per-method table (rates, reference agreement, oracle, false culls,
/// ns/patch), the false-cull list, and with `detail` the sampling/image table.
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
