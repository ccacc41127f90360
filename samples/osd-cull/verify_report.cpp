#include "verify_report.h"

#include "osd_cull/error.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace osd_cull::cli {

namespace {

double percent(uint64_t a, uint64_t b) { return b ? 100.0 * double(a) / double(b) : 0.0; }

const char* const kMethodLegend =
    R"(  cull%        patch-views the GPU kernel culled (bezier%, greg%: of the Bezier, Gregory
               patches)
  ref-cull%    patch-views the double-precision CPU reference culls (on the views it ran)
  agree%       patch-views where the GPU and the reference decide the same
  !in-ref      GPU culls the reference does not make (must be 0)
  oracle-inv%  patch-views with no pixel in the oracle (the unculled draw's item buffer):
               what a perfect cull could take
  false        culled patch-views with oracle pixels (must be 0; - without the oracle)
  ns/patch     median wall time of a view's cull per patch
  drawn%       patch-views the surface test culls but the drawn-triangle bound keeps
)";

const char* const kDetailLegend =
    R"(  false-pixels  oracle pixels of the false culls
  sampled       culled patch-views checked on the sampling grid (--sample)
  sample-viol   of those, with a visible sample (must be 0)
  pixels-lost   pixels covered in the full draw and background in the survivors' draw
                (--image-check; must be 0)
  pixels-changed  pixels another patch covers instead (depth ties; for information)
)";

std::string counted(uint64_t n, const char* what) { return std::to_string(n) + " " + what; }

}  // namespace

VerifyVerdict judgeVerify(std::span<const frame::MethodTotals> totals, bool surfaceExact) {
  VerifyVerdict v;
  // ok: no violation at all. With --surface-exact, silhouette chords (a back-patch-culled
  // patch, back-facing on every sample, whose drawn triangles still cover single oracle
  // pixels that a neighbour covers in the culled image) are reported but do not fail the run.
  for (const auto& t : totals) {
    const bool silhouettes =
        surfaceExact && t.stage == frame::CullStage::BackPatch && t.falseCullPixels == t.falseCulls;
    std::vector<std::string> found;
    if (t.notInReference)
      found.push_back(counted(t.notInReference, "culls outside the double reference"));
    if (t.falseCulls && !silhouettes) found.push_back(counted(t.falseCulls, "false culls"));
    if (t.samplingViolations) found.push_back(counted(t.samplingViolations, "visible samples"));
    if (t.pixelsLost) found.push_back(counted(t.pixelsLost, "lost pixels"));
    v.ok = v.ok && found.empty() && t.falseCulls == 0;
    for (const std::string& f : found) v.failures.push_back(t.name + ": " + f);
  }
  v.okButSilhouettes = v.failures.empty();
  return v;
}

std::string verdictLine(const VerifyVerdict& verdict) {
  if (verdict.failures.empty()) return "PASS";
  std::string line = "FAIL: ";
  for (size_t i = 0; i < verdict.failures.size(); ++i)
    line += (i ? "; " : "") + verdict.failures[i];
  return line;
}

int finishVerify(const VerifyVerdict& verdict, uint64_t validationMessages) {
  std::fflush(stdout);
  if (validationMessages > 0) {
    std::printf("\nFAIL: the validation layers reported %llu messages\n",
                static_cast<unsigned long long>(validationMessages));
    return 1;
  }
  std::printf("\n%s\n", verdictLine(verdict).c_str());
  return verdict.okButSilhouettes ? 0 : 1;
}

void printSkipped(std::span<const std::pair<std::string, std::string>> skipped,
                  const std::string& saidAbove) {
  std::vector<std::pair<std::string, std::string>> byReason;  // names, reason
  for (const auto& [name, why] : skipped) {
    auto it = std::find_if(byReason.begin(), byReason.end(),
                           [&why](const auto& g) { return g.second == why; });
    if (it == byReason.end())
      byReason.push_back({name, why});
    else
      it->first += ", " + name;
  }
  for (auto& [names, why] : byReason) {
    const std::string said = ": " + saidAbove;
    if (!saidAbove.empty() && why.ends_with(said))
      why = why.substr(0, why.size() - said.size()) + " (above)";
    std::printf("skipped %s: %s\n", names.c_str(), why.c_str());
  }
}

VerifyVerdict printVerifyTables(std::span<const frame::MethodTotals> totals, uint32_t patchCount,
                                bool oracle, bool surfaceExact, bool detail) {
  std::printf("\n%-17s %7s %7s %7s %8s %7s %7s %9s %7s %8s %8s\n", "method", "cull%", "bezier%",
              "greg%", "ref-cull%", "agree%", "!in-ref", "oracle-inv%", "false", "ns/patch",
              "drawn%");
  uint64_t silhouetteViews = 0, silhouettePixels = 0;
  for (const auto& t : totals) {
    std::printf("%-17s %7.2f %7.2f %7.2f %8.2f %7.3f %7llu %9.2f %7s %8.0f %8.2f\n", t.name.c_str(),
                100.0 * t.cullRate(), percent(t.culledBezier, t.bezierViews),
                percent(t.culledGregory, t.gregoryViews), 100.0 * t.referenceCullRate(),
                100.0 * t.referenceAgreement(), static_cast<unsigned long long>(t.notInReference),
                100.0 * t.oracleInvisibleRate(),
                oracle ? std::to_string(t.falseCulls).c_str() : "-", t.nsPerPatch(patchCount),
                percent(t.keptForDrawnTriangles, t.patchViews));
    if (t.stage == frame::CullStage::BackPatch) {
      silhouetteViews += t.falseCulls;
      silhouettePixels += t.falseCullPixels;
    }
  }
  std::printf("%s", kMethodLegend);
  if (silhouetteViews > 0)
    std::printf(
        "\nnote: %llu back-patch-culled patch-views have %llu oracle pixels (single "
        "silhouette pixels of drawn chord triangles%s; see "
        "docs/algorithms/drawn-triangles.md)\n",
        static_cast<unsigned long long>(silhouetteViews),
        static_cast<unsigned long long>(silhouettePixels),
        surfaceExact ? ", expected with --surface-exact" : "");
  for (const auto& t : totals)
    for (const auto& f : t.falseCullList)
      std::printf("false cull: %s view %llu patch %u, %u pixels\n", t.name.c_str(),
                  static_cast<unsigned long long>(f.view), f.patch, f.pixels);
  if (detail) {
    std::printf("\n%-17s %12s %12s %12s %12s %14s\n", "method", "false-pixels", "sampled",
                "sample-viol", "pixels-lost", "pixels-changed");
    for (const auto& t : totals)
      std::printf("%-17s %12llu %12llu %12llu %12llu %14llu\n", t.name.c_str(),
                  static_cast<unsigned long long>(t.falseCullPixels),
                  static_cast<unsigned long long>(t.sampledCulls),
                  static_cast<unsigned long long>(t.samplingViolations),
                  static_cast<unsigned long long>(t.pixelsLost),
                  static_cast<unsigned long long>(t.pixelsChanged));
    std::printf("%s", kDetailLegend);
  }
  return judgeVerify(totals, surfaceExact);
}

nlohmann::ordered_json methodJson(const frame::MethodTotals& t, uint32_t patchCount, bool oracle) {
  nlohmann::ordered_json m;
  m["name"] = t.name;
  m["stage"] = frame::toString(t.stage);
  m["cull_rate"] = t.cullRate();
  m["cull_rate_bezier"] = t.bezierViews ? double(t.culledBezier) / double(t.bezierViews) : 0.0;
  m["cull_rate_gregory"] = t.gregoryViews ? double(t.culledGregory) / double(t.gregoryViews) : 0.0;
  m["culled_per_view"] = t.views ? double(t.culled) / double(t.views) : 0.0;
  m["kept_for_drawn_triangles_rate"] =
      t.patchViews ? double(t.keptForDrawnTriangles) / double(t.patchViews) : 0.0;
  m["false_culls"] = oracle ? nlohmann::ordered_json(t.falseCulls) : nlohmann::ordered_json();
  m["false_cull_pixels"] =
      oracle ? nlohmann::ordered_json(t.falseCullPixels) : nlohmann::ordered_json();
  m["oracle_invisible_rate"] =
      oracle ? nlohmann::ordered_json(t.oracleInvisibleRate()) : nlohmann::ordered_json();
  m["ns_per_patch"] = t.nsPerPatch(patchCount);
  m["reference_views"] = t.referenceViews;
  m["reference_cull_rate"] = t.referenceCullRate();
  m["cpu_reference_agreement"] = t.referenceAgreement();
  m["culled_not_in_reference"] = t.notInReference;
  m["sampled_culls"] = t.sampledCulls;
  m["sampling_violations"] = t.samplingViolations;
  m["image_views"] = t.imageViews;
  m["pixels_lost"] = t.pixelsLost;
  m["pixels_changed"] = t.pixelsChanged;
  return m;
}

void accumulate(frame::MethodTotals& a, const frame::MethodTotals& b) {
  a.views += b.views;
  a.patchViews += b.patchViews;
  a.culled += b.culled;
  a.culledBezier += b.culledBezier;
  a.culledGregory += b.culledGregory;
  a.keptForDrawnTriangles += b.keptForDrawnTriangles;
  a.bezierViews += b.bezierViews;
  a.gregoryViews += b.gregoryViews;
  a.referenceViews += b.referenceViews;
  a.referencePatchViews += b.referencePatchViews;
  a.referenceCulled += b.referenceCulled;
  a.agreements += b.agreements;
  a.notInReference += b.notInReference;
  a.oracleViews += b.oracleViews;
  a.oraclePatchViews += b.oraclePatchViews;
  a.oracleInvisible += b.oracleInvisible;
  a.falseCulls += b.falseCulls;
  a.falseCullPixels += b.falseCullPixels;
  for (const auto& f : b.falseCullList)
    if (a.falseCullList.size() < 64) a.falseCullList.push_back(f);
  a.culledOnOracleViews += b.culledOnOracleViews;
  a.sampledCulls += b.sampledCulls;
  a.samplingViolations += b.samplingViolations;
  a.imageViews += b.imageViews;
  a.pixelsLost += b.pixelsLost;
  a.pixelsChanged += b.pixelsChanged;
  a.wallMs.insert(a.wallMs.end(), b.wallMs.begin(), b.wallMs.end());
}

void finishVerifyJson(nlohmann::ordered_json out,
                      std::span<const std::pair<std::string, std::string>> skipped,
                      const VerifyVerdict& verdict, const std::string& path) {
  out["skipped"] = nlohmann::ordered_json::array();
  for (const auto& [name, why] : skipped)
    out["skipped"].push_back({{"name", name}, {"reason", why}});
  out["ok"] = verdict.ok;
  out["ok_except_silhouette_chords"] = verdict.okButSilhouettes;
  std::ofstream file(path);
  if (!(file << out.dump(2) << "\n")) throw Error(path + ": cannot write");
  std::printf("\nwrote %s\n", path.c_str());
}

}  // namespace osd_cull::cli
