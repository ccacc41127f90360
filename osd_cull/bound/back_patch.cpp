#include "osd_cull/bound/back_patch.h"

namespace osd_cull::bound {

const char* toString(BackPatchVerdict verdict) {
  switch (verdict) {
    case BackPatchVerdict::BackFacing:
      return "back-facing";
    case BackPatchVerdict::FrontFacing:
      return "front-facing";
    case BackPatchVerdict::Silhouette:
      return "silhouette";
    case BackPatchVerdict::EyeOutsideBackRegion:
      return "eye-outside-back-region";
    case BackPatchVerdict::NonFinite:
      return "non-finite";
    case BackPatchVerdict::NoNormal:
      return "no-normal";
    case BackPatchVerdict::WideCone:
      return "wide-cone";
    case BackPatchVerdict::NoFiniteEye:
      return "no-finite-eye";
    case BackPatchVerdict::DrawnTriangles:
      return "drawn-triangles";
  }
  return "unknown";
}

}  // namespace osd_cull::bound
