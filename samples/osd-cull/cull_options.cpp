#include "cull_options.h"

#include "option_checks.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_methods.h"

namespace osd_cull::cli {

void addCullOptions(CLI::App& app, CullArgs& args) {
  const std::string group = "Culling";
  app.add_option("--cull", args.mode,
                 "cull patches on the GPU before drawing, and draw only the survivors:\n"
                 "none, frustum, backpatch, occlusion, all (frustum + back-patch +\n"
                 "occlusion); default: the effect plan chooses (--plan). With occlusion\n"
                 "a frame has two passes\n"
                 "(Niessner & Loop): draw the patches visible last frame, build a Hi-Z\n"
                 "pyramid of that depth, run the cull kernel on every patch, draw the\n"
                 "patches that became visible")
      ->type_name("MODE")
      ->group(group)
      ->check(oneOf({"none", "frustum", "backpatch", "occlusion", "all"}));
  app.add_option("--backpatch-method", args.backPatchMethod,
                 "back-patch test: tcone, ncone, tangent-plane (default),\n"
                 "tangent-plane-16; used only on closed, outward-oriented meshes.\n"
                 "With the plan (no --cull): the one method it may choose")
      ->type_name("M")
      ->group(group)
      ->check(oneOf(frame::cullMethodNames(frame::CullStage::BackPatch), "a back-patch method"));
  app.add_flag("--surface-exact", args.surfaceExact,
               "back-patch tests exact for the surface only, as the papers measure\n"
               "them (default: also conservative for the drawn chord triangles,\n"
               "which culls less but never takes a pixel; docs/algorithms/\n"
               "drawn-triangles.md)")
      ->group(group);
  app.add_flag("--clusters", args.clusters,
               "test clusters of patches first (Zachmann's clustered back-face\n"
               "culling): clusters outside the frustum or back-facing are culled\n"
               "whole, inside and front-facing ones drawn untested, only the rest\n"
               "tested patch by patch (docs/algorithms/clusters.md); static meshes,\n"
               "tcone or ncone, no occlusion")
      ->group(group);
  app.add_flag("--aggressive", args.aggressive,
               "occlusion: skip the second pass (newly visible patches appear one\n"
               "frame late)")
      ->group(group);
  app.add_option("--draw-mode", args.drawMode,
                 "occlusion: filtered (compact indirect draws, default) or tf0 (every\n"
                 "patch, tessellation factor 0 for the ones not drawn)")
      ->type_name("M")
      ->group(group)
      ->check(oneOf({"filtered", "tf0"}));
  app.add_option("--first-frame", args.firstFrame,
                 "occlusion: status before the first frame: all (default), half, none")
      ->type_name("P")
      ->group(group)
      ->check(oneOf({"all", "half", "none"}));
  app.add_flag("--hiz-full", args.hizFull,
               "occlusion: top pyramid level at full resolution (default: half)")
      ->group(group);
  app.add_flag("--hiz-tight", args.hizTight,
               "occlusion: look boxes up one level finer when 2x2 texels still\n"
               "cover them (default: the paper's ceil(log2) level)")
      ->group(group);
  app.add_option("--hiz-reduction", args.hizReduction,
                 "occlusion: auto (default: blocked), blocked (three levels per\n"
                 "dispatch from a copy of the depth), sampler (min/max sampler, a\n"
                 "dispatch per level) or fourtap")
      ->type_name("R")
      ->group(group)
      ->check(oneOf({"auto", "blocked", "sampler", "fourtap"}));
}

CullChoice cullChoice(const CullArgs& args) {
  CullChoice c;
  c.mode = args.mode.empty() ? "none" : args.mode;
  c.backPatchMethodGiven = !args.backPatchMethod.empty();
  if (c.backPatchMethodGiven) {
    c.backPatchMethod = args.backPatchMethod;
    if (!args.mode.empty() && c.mode != "backpatch" && c.mode != "all")
      throw UsageError(
          "--backpatch-method needs --cull backpatch, --cull all, or the plan (no "
          "--cull): --cull " +
          c.mode + " runs no back-patch test");
  }
  if (args.surfaceExact) {
    if (c.mode != "backpatch" && c.mode != "all")
      throw UsageError("--surface-exact needs --cull backpatch or --cull all");
    c.surfaceExact = true;
  }
  if (args.clusters) {
    if (!c.enabled()) throw UsageError("--clusters needs --cull frustum, backpatch or all");
    c.clusters = true;
  }
  frame::CullFrameOptions& f = c.frame;
  f.aggressive = args.aggressive;
  if (args.drawMode == "tf0") f.drawMode = frame::CullDrawMode::TessFactorZero;
  if (args.firstFrame == "half") f.firstFrame = frame::FirstFrame::HalfVisible;
  if (args.firstFrame == "none") f.firstFrame = frame::FirstFrame::NoneVisible;
  f.hiz.fullResolution = args.hizFull;
  if (args.hizTight) f.hiz.lookup = bound::HiZLookup::Tight;
  if (args.hizReduction == "blocked") f.hiz.reduction = frame::HiZReduction::Blocked;
  if (args.hizReduction == "sampler") f.hiz.reduction = frame::HiZReduction::Sampler;
  if (args.hizReduction == "fourtap") f.hiz.reduction = frame::HiZReduction::FourTap;
  const bool frameOption = args.aggressive || !args.drawMode.empty() || !args.firstFrame.empty() ||
                           args.hizFull || args.hizTight || !args.hizReduction.empty();
  if (frameOption && !c.occlusion())
    throw UsageError(
        "--aggressive, --draw-mode, --first-frame and --hiz-* need --cull occlusion "
        "or --cull all");
  return c;
}

frame::CullSettings cullSettings(const CullChoice& choice,
                                 const bound::BackPatchValidity& validity) {
  frame::CullSettings s;
  s.frustum = choice.mode == "frustum" || choice.mode == "all";
  if (choice.mode == "backpatch" || choice.mode == "all") s.backPatch = choice.backPatchMethod;
  if (choice.occlusion()) s.occlusion = "hiz";
  s.backPatchValidity = validity;
  s.drawnTriangles = !choice.surfaceExact;
  if (choice.clusters) {  // the cluster bounds are built once: the points must not move
    s.clusters = true;
    s.staticPoints = true;
  }
  return s;
}

}  // namespace osd_cull::cli
