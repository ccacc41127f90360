#include "cull_report.h"

#include "adapters/image_png.h"

#include <cmath>
#include <cstdio>

namespace osd_cull::cli {

namespace {

unsigned long long u64(uint64_t v) { return static_cast<unsigned long long>(v); }

// One "ms" layout for every frame, culled or not: the stages pass1, pyramid, cull and
// pass2 on the GPU (timestamps in the frame's one submission; null when the device has
// none, with the reason in "note"), "gpu" their sum, "total" the wall clock of the frame
// (recording, submission, wait).
nlohmann::json msJson(const frame::CullStageTimes& t, double wallMs, const std::string& note) {
  auto value = [](double v) { return std::isnan(v) ? nlohmann::json() : nlohmann::json(v); };
  nlohmann::json ms{{"pass1", value(t.pass1)}, {"pyramid", value(t.pyramid)},
                    {"cull", value(t.cull)},   {"pass2", value(t.pass2)},
                    {"gpu", value(t.total)},   {"total", wallMs}};
  if (!note.empty()) ms["note"] = note;
  return ms;
}

nlohmann::json cullFrameMs(const frame::CullFrameStats& s) {
  nlohmann::json ms = msJson(s.gpu, s.totalMs(), s.gpuNote);
  // The diagnostic mode's wall clock of each pass's own submission, when it ran.
  if (s.pass1Ms + s.pyramidMs + s.cullMs + s.pass2Ms > 0.0)
    ms["wallPerSubmission"] = {
        {"pass1", s.pass1Ms}, {"pyramid", s.pyramidMs}, {"cull", s.cullMs}, {"pass2", s.pass2Ms}};
  return ms;
}

// An unculled frame is one pass: no pyramid, cull or second pass.
nlohmann::json plainFrameMs(const frame::FrameStats& s) {
  frame::CullStageTimes t;
  if (s.gpuMs > 0.0) t = {s.gpuMs, 0.0, 0.0, 0.0, s.gpuMs};
  return msJson(t, s.wallMs, s.gpuMs > 0.0 ? "" : "no timestamps on this device");
}

}  // namespace

std::string cullFrameLine(uint32_t frame, const frame::CullFrameStats& s) {
  char line[512];
  std::snprintf(
      line, sizeof(line),
      "frame %u: %u patches, drawn pass 1 %u, pass 2 %u; culled frustum %u, back-patch %u, "
      "occlusion %u; TES invocations %llu (pass 1 %llu, pass 2 %llu), fragment invocations "
      "%llu; ms: ",
      frame, s.patchesTotal, s.drawnPass1, s.drawnPass2, s.culledFrustum, s.culledBackPatch,
      s.culledOcclusion, u64(s.pass1.tessEvaluationInvocations + s.pass2.tessEvaluationInvocations),
      u64(s.pass1.tessEvaluationInvocations), u64(s.pass2.tessEvaluationInvocations),
      u64(s.pass1.fragmentShaderInvocations + s.pass2.fragmentShaderInvocations));
  char times[200];
  // The diagnostic mode's split (CullFrameOptions::timePasses) is the wall clock of each
  // pass's own submission; otherwise the GPU timestamps of the one submission.
  if (s.pass1Ms + s.pyramidMs + s.cullMs + s.pass2Ms > 0.0)
    std::snprintf(times, sizeof(times),
                  "pass 1 %.2f, pyramid %.2f, cull %.2f, pass 2 %.2f, total %.2f (a submission "
                  "per pass)",
                  s.pass1Ms, s.pyramidMs, s.cullMs, s.pass2Ms, s.totalMs());
  else if (s.gpu.measured())
    std::snprintf(times, sizeof(times),
                  "total %.2f (one submission); GPU: pass 1 %.2f, pyramid %.2f, cull %.2f, "
                  "pass 2 %.2f",
                  s.totalMs(), s.gpu.pass1, s.gpu.pyramid, s.gpu.cull, s.gpu.pass2);
  else
    std::snprintf(times, sizeof(times), "total %.2f (one submission)", s.totalMs());
  std::string clusters;
  if (s.clusters.clusters > 0)
    clusters = "; clusters " + std::to_string(s.clusters.clusters) + ": culled " +
               std::to_string(s.clusters.culled) + ", accepted " +
               std::to_string(s.clusters.accepted) + ", undecided " +
               std::to_string(s.clusters.undecided) + ", per-patch invocations " +
               std::to_string(s.clusters.perPatchInvocations);
  return std::string(line) + times + clusters;
}

nlohmann::json cullFrameJson(uint32_t frame, const frame::CullFrameStats& s) {
  auto pass = [](const vulkan::PipelineStatistics& p) {
    return nlohmann::json{{"tessControlPatches", p.tessControlPatches},
                          {"tessEvaluationInvocations", p.tessEvaluationInvocations},
                          {"fragmentShaderInvocations", p.fragmentShaderInvocations},
                          {"clippingPrimitives", p.clippingPrimitives}};
  };
  return {{"frame", frame},
          {"patches", s.patchesTotal},
          {"drawnPass1", s.drawnPass1},
          {"drawnPass2", s.drawnPass2},
          {"survivors", s.survivors},
          {"newlyVisible", s.newlyVisible},
          {"culled",
           {{"frustum", s.culledFrustum},
            {"backPatch", s.culledBackPatch},
            {"occlusion", s.culledOcclusion}}},
          {"pass1", pass(s.pass1)},
          {"pass2", pass(s.pass2)},
          {"ms", cullFrameMs(s)},
          {"clusters",
           {{"tests", s.clusters.clusters},
            {"culled", s.clusters.culled},
            {"accepted", s.clusters.accepted},
            {"undecided", s.clusters.undecided},
            {"perPatchInvocations", s.clusters.perPatchInvocations}}}};
}

nlohmann::json plainFrameJson(uint32_t frame, const frame::FrameStats& s) {
  return {{"frame", frame},
          {"patches", s.patchesDrawn},
          {"drawCalls", s.drawCalls},
          {"tessEvaluationInvocations", s.statistics.tessEvaluationInvocations},
          {"fragmentShaderInvocations", s.statistics.fragmentShaderInvocations},
          {"ms", plainFrameMs(s)}};
}

uint32_t writePyramidLevels(const std::filesystem::path& dir, const frame::HiZPyramid& pyramid,
                            vulkan::Context& context) {
  std::filesystem::create_directories(dir);
  const auto levels = pyramid.readLevels(context);
  const auto& layout = pyramid.layout();
  for (uint32_t l = 0; l < levels.size(); ++l) {
    char name[32];
    std::snprintf(name, sizeof(name), "hiz_level_%02u.png", l);
    adapters::writePng(
        dir / name, adapters::depthImage(layout.levelWidth(l), layout.levelHeight(l), levels[l]));
  }
  return static_cast<uint32_t>(levels.size());
}

nlohmann::json summaryJson(const session::SessionSummary& s) {
  nlohmann::json j{{"frames", s.frames},
                   {"ms", {{"mean", s.meanMs}, {"median", s.medianMs}}},
                   {"patches", s.patches},
                   {"drawn", s.drawn},
                   {"tes", {{"invocations", s.tesInvocations}, {"saved", s.tesSaved}}},
                   {"configurations", s.configurations}};
  if (s.predictedMeanMs > 0.0)
    j["plan"] = {{"changes", s.planChanges}, {"predicted_mean_ms", s.predictedMeanMs}};
  return j;
}

}  // namespace osd_cull::cli
