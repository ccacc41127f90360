#include "cull_options.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/cull/cull_methods.h"

namespace osd_cull::cli {

const char* const kCullOptionsUsage =
    R"(  --cull MODE            cull patches on the GPU before drawing, and draw only the survivors:
                         none (default), frustum, backpatch, occlusion, all (frustum +
                         back-patch + occlusion). With occlusion a frame has two passes
                         (Niessner & Loop): draw the patches visible last frame, build a Hi-Z
                         pyramid of that depth, run the cull kernel on every patch, draw the
                         patches that became visible
  --backpatch-method M   back-patch test: tcone, ncone, tangent-plane (default),
                         tangent-plane-16; used only on closed, outward-oriented meshes
  --surface-exact        back-patch tests exact for the surface only, as the papers measure
                         them (default: also conservative for the drawn chord triangles,
                         which culls less but never takes a pixel; docs/algorithms/
                         drawn-triangles.md)
  --aggressive           occlusion: skip the second pass (newly visible patches appear one
                         frame late)
  --draw-mode M          occlusion: filtered (compact indirect draws, default) or tf0 (every
                         patch, tessellation factor 0 for the ones not drawn)
  --first-frame P        occlusion: status before the first frame: all (default), half, none
  --hiz-full             occlusion: top pyramid level at full resolution (default: half)
  --hiz-tight            occlusion: look boxes up one level finer when 2x2 texels still
                         cover them (default: the paper's ceil(log2) level)
  --hiz-reduction R      occlusion: auto (default), sampler (min/max sampler) or fourtap
)";

CullChoice cullChoiceFromArgs(Args& args) {
  CullChoice c;
  if (auto mode = args.value("cull")) {
    if (*mode != "none" && *mode != "frustum" && *mode != "backpatch" && *mode != "occlusion" &&
        *mode != "all")
      throw Error("option --cull: '" + *mode +
                  "' is not one of none, frustum, backpatch, occlusion, all");
    c.mode = *mode;
  }
  if (auto method = args.value("backpatch-method")) {
    if (frame::cullMethod(*method).stage != frame::CullStage::BackPatch)
      throw Error("option --backpatch-method: '" + *method + "' is not a back-patch method");
    c.backPatchMethod = *method;
  }
  if (args.flag("surface-exact")) {
    if (c.mode != "backpatch" && c.mode != "all")
      throw Error("--surface-exact needs --cull backpatch or --cull all");
    c.surfaceExact = true;
  }
  frame::CullFrameOptions& f = c.frame;
  bool frameOption = false;
  if (args.flag("aggressive")) f.aggressive = frameOption = true;
  if (auto mode = args.value("draw-mode")) {
    frameOption = true;
    if (*mode == "filtered")
      f.drawMode = frame::CullDrawMode::Filtered;
    else if (*mode == "tf0")
      f.drawMode = frame::CullDrawMode::TessFactorZero;
    else
      throw Error("option --draw-mode: '" + *mode + "' is not one of filtered, tf0");
  }
  if (auto first = args.value("first-frame")) {
    frameOption = true;
    if (*first == "all")
      f.firstFrame = frame::FirstFrame::AllVisible;
    else if (*first == "half")
      f.firstFrame = frame::FirstFrame::HalfVisible;
    else if (*first == "none")
      f.firstFrame = frame::FirstFrame::NoneVisible;
    else
      throw Error("option --first-frame: '" + *first + "' is not one of all, half, none");
  }
  if (args.flag("hiz-full")) f.hiz.fullResolution = frameOption = true;
  if (args.flag("hiz-tight")) {
    f.hiz.lookup = bound::HiZLookup::Tight;
    frameOption = true;
  }
  if (auto reduction = args.value("hiz-reduction")) {
    frameOption = true;
    if (*reduction == "auto")
      f.hiz.reduction = frame::HiZReduction::Auto;
    else if (*reduction == "sampler")
      f.hiz.reduction = frame::HiZReduction::Sampler;
    else if (*reduction == "fourtap")
      f.hiz.reduction = frame::HiZReduction::FourTap;
    else
      throw Error("option --hiz-reduction: '" + *reduction +
                  "' is not one of auto, sampler, fourtap");
  }
  if (frameOption && !c.occlusion())
    throw Error(
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
  return s;
}

}  // namespace osd_cull::cli
