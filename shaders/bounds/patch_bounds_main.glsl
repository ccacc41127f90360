// The bounds pass (osd_cull/frame/cull/bounds_pass.h): one thread per patch recomputes
// from the current control points everything the back-patch methods read, in the layout
// CullPass packs host cones (cull_layout.h kConeVec4s), or (kBoundsOutputDisplaced) the
// cones of the displaced kernels (Niessner & Loop §4.2: ACoN from the tangent cones, CoN
// from the normal patch) next to the patch's static Dmin/Dmax. The host prepends
// "#version 450" and the Gregory index tables (gregory_bounds.glsl).
#include "bezier_bounds.glsl"
#include "gregory_bounds.glsl"

layout(local_size_x = kBoundsGroupSize) in;

void main() {
  // A 2D dispatch past maxComputeWorkGroupCount[0] groups (vulkan::checkedGroups2D).
  uint p = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * kBoundsGroupSize +
           gl_LocalInvocationIndex;
  if (p >= pc.patchCount) return;
  uint first = firstPoint(p);
  gBase = gl_LocalInvocationIndex * kMaxVectors;
  uint count = isBezier(p) ? 16u : 20u;
  bool displaced = pc.outputKind == kBoundsOutputDisplaced;
  bool finite = true;
  loadPatchPoints(first, count);
  [[dont_unroll]] for (uint k = 0u; k < count; ++k) finite = finite && isFiniteF(pointAt(k));
  // Without a cone (non-finite points, kBoundsNoCone, a tangent-plane Bezier patch): the
  // placeholder of bound::buildPatchCones; the displaced kernels then extend by max |D|.
  DirCone cone = invalidCone(kVerdictNonFinite);
  if (!finite) {
    if (displaced)
      writeDisplaced(p, cone);
    else
      writeCone(p, cone, vec3(0.0), 0.0, vec4(0.0));
    return;
  }
  vec4 derivatives = vec4(0.0);  // Gregory: no G, H, min |N| (as the host packing)
  if (isBezier(p)) {
    float minNormal = 0.0;
    if (pc.method == kBoundsNCone)
      cone = normalCone(minNormal);
    else if (pc.method == kBoundsTCone)
      cone = tangentCone(minNormal);
    if (!displaced) derivatives = vec4(derivativeBounds(), minNormal);
  } else if (pc.method != kBoundsNoCone) {
    cone = gregoryCone(first);
  }
  if (pc.shrink > 0.0) {  // tests only: bounds that must be caught as too tight
    if (cone.valid) cone = coneFromSine(cone.axis, max(0.0, cone.sinAngle - pc.shrink));
    derivatives *= vec4(vec3(1.0 - pc.shrink), 1.0 + pc.shrink);
  }
  if (displaced) {
    writeDisplaced(p, cone);
    return;
  }
  vec3 apex = vec3(0.0);
  float maxRadius = 0.0;
  if (cone.valid) placeApex(cone, first, count, apex, maxRadius);
  writeCone(p, cone, apex, maxRadius, derivatives);
}
