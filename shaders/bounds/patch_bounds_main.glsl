// The bounds pass (osd_cull/frame/cull/bounds_pass.h): one thread per patch recomputes
// from the current control points everything the cone back-patch methods read, in the
// layout CullPass packs host cones (cull_layout.h kConeVec4s). The host prepends
// "#version 450" and the Gregory index tables (gregory_bounds.glsl).
#include "bezier_bounds.glsl"
#include "gregory_bounds.glsl"

layout(local_size_x = kBoundsGroupSize) in;

void main() {
  uint p = gl_GlobalInvocationID.x;
  if (p >= pc.patchCount) return;
  uint first = firstPoint(p);
  gBase = gl_LocalInvocationIndex * kMaxVectors;
  uint count = isBezier(p) ? 16u : 20u;
  bool finite = true;
  loadPatchPoints(first, count);
  [[dont_unroll]] for (uint k = 0u; k < count; ++k) finite = finite && isFiniteF(pointAt(k));
  if (!finite) {
    writeCone(p, invalidCone(kVerdictNonFinite), vec3(0.0), 0.0, vec4(0.0));
    return;
  }
  DirCone cone;
  vec4 derivatives = vec4(0.0);  // Gregory: no G, H, min |N| (as the host packing)
  if (isBezier(p)) {
    float minNormal;
    cone = pc.method == kBoundsNCone ? normalCone(minNormal) : tangentCone(minNormal);
    derivatives = vec4(derivativeBounds(), minNormal);
  } else {
    cone = gregoryCone(first);
  }
  if (pc.shrink > 0.0) {  // tests only: bounds that must be caught as too tight
    if (cone.valid) cone = coneFromSine(cone.axis, max(0.0, cone.sinAngle - pc.shrink));
    derivatives *= vec4(vec3(1.0 - pc.shrink), 1.0 + pc.shrink);
  }
  vec3 apex = vec3(0.0);
  float maxRadius = 0.0;
  if (cone.valid) placeApex(cone, first, count, apex, maxRadius);
  writeCone(p, cone, apex, maxRadius, derivatives);
}
