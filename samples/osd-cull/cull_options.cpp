#include "cull_options.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/cull_methods.h"

namespace osd_cull::cli {

const char* const kCullOptionsUsage =
    R"(  --cull MODE            cull patches on the GPU before drawing, and draw only the survivors:
                         none (default), frustum, backpatch, all (frustum + back-patch)
  --backpatch-method M   back-patch test: tcone, ncone, tangent-plane (default),
                         tangent-plane-16; used only on closed, outward-oriented meshes
)";

CullChoice cullChoiceFromArgs(Args& args) {
  CullChoice c;
  if (auto mode = args.value("cull")) {
    if (*mode != "none" && *mode != "frustum" && *mode != "backpatch" && *mode != "all")
      throw Error("option --cull: '" + *mode + "' is not one of none, frustum, backpatch, all");
    c.mode = *mode;
  }
  if (auto method = args.value("backpatch-method")) {
    if (frame::cullMethod(*method).stage != frame::CullStage::BackPatch)
      throw Error("option --backpatch-method: '" + *method + "' is not a back-patch method");
    c.backPatchMethod = *method;
  }
  return c;
}

frame::CullSettings cullSettings(const CullChoice& choice,
                                 const bound::BackPatchValidity& validity) {
  frame::CullSettings s;
  s.frustum = choice.mode == "frustum" || choice.mode == "all";
  if (choice.mode == "backpatch" || choice.mode == "all") s.backPatch = choice.backPatchMethod;
  s.backPatchValidity = validity;
  return s;
}

}  // namespace osd_cull::cli
