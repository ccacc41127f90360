// Resources and the conservative fp32 direction cone shared by the bounds pass
// (patch_bounds_main.glsl). Every quantity written bounds the double-precision reference
// (osd_cull/bound/cone_of_normals.cpp, drawn_triangles.cpp) computed from the exact
// control points, which differ from the device's by at most pc.pointError per coordinate;
// the margins are derived in docs/algorithms/bounds-pass.md. u = 2^-24 is the fp32 unit
// roundoff; trigonometric functions are only trusted to the Vulkan precision (asin, acos,
// atan: 4096 ulp, covered by kTrigSlack; sin: 2^-11 absolute).
#ifndef OSD_CULL_BOUNDS_COMMON_GLSL
#define OSD_CULL_BOUNDS_COMMON_GLSL
#include <shared/bounds_layout.h>
#include <shared/cull_layout.h>

layout(push_constant) uniform Push { BoundsConstants pc; };

#define POINTS_BINDING kBoundsBindingPoints  // read by common/control_points.glsl
layout(std430, set = 0, binding = kBoundsBindingCones) writeonly buffer Cones { vec4 cones[]; };
// (Dmin, Dmax) per patch, rounded outward on the host: copied into the displaced output.
layout(std430, set = 0, binding = kBoundsBindingRanges) readonly buffer Ranges { vec2 ranges[]; };
// kMaxVectors vec4 (xyz, error) per invocation: the vectors a cone is built from. Shared
// memory, not a private array: lavapipe turns dynamically indexed private arrays into
// select ladders and took minutes to compile this kernel with them.
shared vec4 scratch[kBoundsGroupSize * kMaxVectors];
// The patch's control points, copied once from the points buffer (each is read many times;
// storage-buffer reads are the slow part of this kernel on lavapipe).
shared vec3 patchPoints[kBoundsGroupSize * 20u];

const float kU = 1.0 / 16777216.0;
const float kTrigSlack = 1.0 / 1024.0;
const float kSinAbsError = 1.0 / 2048.0;

#include "../common/patch_points.glsl"

// |computed difference of two device points - exact difference of the reference points|:
// each point is off by pc.pointError per coordinate (sqrt(3) of it in length, twice), the
// subtraction rounds by u per coordinate.
float differenceError(vec3 v) { return 3.5 * pc.pointError + 2.0 * kU * length(v); }

// The vectors a cone must hold, each with a bound of its absolute error (exact zeros are
// skipped, as in the reference: they add nothing to a non-negative combination).
uint gBase = 0u;    // this invocation's first scratch slot
uint gPoints = 0u;  // this invocation's first patchPoints slot

// Control point k of the patch (after loadPatchPoints).
vec3 pointAt(uint k) { return patchPoints[gPoints + k]; }
void loadPatchPoints(uint first, uint count) {
  gPoints = gl_LocalInvocationIndex * 20u;
  [[dont_unroll]] for (uint k = 0u; k < count; ++k) patchPoints[gPoints + k] = controlPoint(first + k);
}
uint gCount = 0u;

vec3 vecAt(uint i) { return scratch[gBase + i].xyz; }
float errAt(uint i) { return scratch[gBase + i].w; }
void setVector(uint i, vec3 v, float error) { scratch[gBase + i] = vec4(v, error); }
void addVector(vec3 v, float error) {
  setVector(gCount, v, error);
  ++gCount;
}

// A cone of directions: every exact vector lies within the angle of sine sinAngle
// (< 1, an upper bound) of the unit axis; cosAngle is a lower bound of its cosine.
struct DirCone {
  vec3 axis;
  float sinAngle;
  float cosAngle;
  bool valid;
  uint reason;  // BackPatchVerdict when invalid
};

DirCone invalidCone(uint reason) { return DirCone(vec3(0.0, 0.0, 1.0), 1.0, 0.0, false, reason); }

DirCone coneFromSine(vec3 axis, float s) {
  if (!(s < 1.0)) return invalidCone(kVerdictWideCone);
  // 1 - s and 1 + s are exact or within u; the product and sqrt within 3u.
  return DirCone(axis, s, sqrt((1.0 - s) * (1.0 + s)) * (1.0 - 4.0 * kU), true, 0u);
}

// The smallest cosine from `axis` to the vectors, as computed (chooses the axis only).
float approxMinCos(vec3 axis, out uint farthest) {
  float worst = 2.0;
  farthest = 0u;
  [[dont_unroll]] for (uint i = 0u; i < gCount; ++i) {
    float len = length(vecAt(i));
    if (len == 0.0) continue;
    float c = dot(axis, vecAt(i)) / len;
    if (c <= worst) worst = c, farthest = i;
  }
  return worst;
}

// bound::boundDirections in fp32: the axis is the better of the normalized mean of the unit
// vectors and eight Badoiu-Clarkson steps; the angle is then bounded for that axis. Per
// vector v (computed) with error e: sin of the angle to the axis <= sin θ1 + sin θ2 with
// θ1 the angle to v (cross product, rounding <= 8u) and sin θ2 = e / |v|, valid when
// θ1 + θ2 < 90° (checked as cos θ1 cos θ2 > sin θ1 sin θ2 with rounded bounds).
DirCone boundDirections() {
  vec3 sum = vec3(0.0);
  uint used = 0u;
  [[dont_unroll]] for (uint i = 0u; i < gCount; ++i) {
    float len = length(vecAt(i));
    if (len == 0.0) continue;
    if (!(len > errAt(i)) || !isFiniteF(len)) return invalidCone(kVerdictWideCone);
    sum += vecAt(i) / len;
    ++used;
  }
  if (used == 0u) return invalidCone(kVerdictNoNormal);
  if (!(length(sum) > 0.0)) return invalidCone(kVerdictWideCone);
  vec3 axis = normalize(sum);
  uint far;
  float best = approxMinCos(axis, far);
  vec3 centre = axis;
  [[dont_unroll]] for (int k = 1; k <= 8; ++k) {
    // `far` is the farthest vector from normalize(centre): from the evaluation of the
    // previous candidate (the reference recomputes it; the result is the same).
    centre += (vecAt(far) / length(vecAt(far)) - centre) / float(k + 1);
    if (!(length(centre) > 0.0)) break;
    vec3 candidate = normalize(centre);
    float c = approxMinCos(candidate, far);
    if (c > best) best = c, axis = candidate;
  }
  float axisLength = length(axis);
  float s = 0.0;
  [[dont_unroll]] for (uint i = 0u; i < gCount; ++i) {
    float len = length(vecAt(i));
    if (len == 0.0) continue;
    float scale = 1.0 / (axisLength * len);
    float s1 = length(cross(axis, vecAt(i))) * scale * (1.0 + 8.0 * kU) + 8.0 * kU;
    float c1 = dot(axis, vecAt(i)) * scale - 8.0 * kU;
    float s2 = errAt(i) / len * (1.0 + 4.0 * kU);
    float c2 = sqrt(max(0.0, 1.0 - s2 * s2 - 2.0 * kU)) * (1.0 - 4.0 * kU);
    if (!(c1 > 0.0) || !(c1 * c2 > s1 * s2 * (1.0 + 4.0 * kU) + 4.0 * kU))
      return invalidCone(kVerdictWideCone);
    s = max(s, (s1 + s2) * (1.0 + 2.0 * kU));
  }
  return coneFromSine(axis, s);
}

// Sederberg and Meyers (bound::combineTangentCones): tangents within α of a, bitangents
// within β of b give normals within γ of a x b / |a x b|, sin²γ = (sin²α + 2 sinα sinβ
// |cos θ| + sin²β) / sin²θ. In fp32: sin θ rounded down and |cos θ| up by 8u (cross and dot
// of unit-length axes, lengths 1 ± 2u), and γ grows by the angle between the computed axis
// and the exact one, below 8u / sin θ + 4u.
DirCone combineTangentCones(DirCone tu, DirCone tv) {
  if (!tu.valid) return tu;
  if (!tv.valid) return tv;
  vec3 c = cross(tu.axis, tv.axis);
  float sinTheta = length(c) * (1.0 - 4.0 * kU) - 8.0 * kU;
  float cosTheta = abs(dot(tu.axis, tv.axis)) + 8.0 * kU;
  if (!(sinTheta > 0.0)) return invalidCone(kVerdictWideCone);
  float sa = tu.sinAngle, sb = tv.sinAngle;
  float sin2 = (sa * sa + 2.0 * sa * sb * cosTheta + sb * sb) * (1.0 + 8.0 * kU) /
               (sinTheta * sinTheta);
  if (!(sin2 < 1.0)) return invalidCone(kVerdictWideCone);
  float s = sqrt(sin2) * (1.0 + 4.0 * kU) + 8.0 * kU / sinTheta + 4.0 * kU;
  return coneFromSine(normalize(c), s);
}

// An upper bound of the half-angle in radians (asin to the Vulkan precision).
float coneAngle(DirCone cone) { return asin(min(1.0, cone.sinAngle)) * (1.0 + kTrigSlack) + 4.0 * kU; }

// withApex of cone_of_normals.cpp: l = c - t a with the smallest t such that every point is
// within 90° - γ of the axis seen from l (h + t >= ρ tan γ), plus what covers the points'
// error, the rounding of h and ρ (below 16u of the magnitudes) and of the apex itself
// (a lateral shift ε of the apex is covered by moving it back ε (1 + tan γ)).
void placeApex(inout DirCone cone, uint first, uint count, out vec3 apex, out float maxRadius) {
  vec3 centre = vec3(0.0);
  float maxAbs = 0.0;
  [[dont_unroll]] for (uint k = 0u; k < count; ++k) {
    vec3 p = pointAt(k);
    centre += p;
    maxAbs = max(maxAbs, max(abs(p.x), max(abs(p.y), abs(p.z))));
  }
  centre /= float(count);
  float tanGamma = cone.sinAngle / cone.cosAngle * (1.0 + 4.0 * kU);
  float t = -3.0e38, radius = 0.0, rho = 0.0;
  [[dont_unroll]] for (uint k = 0u; k < count; ++k) {
    vec3 d = pointAt(k) - centre;
    float h = dot(d, cone.axis);
    float r = length(d - h * cone.axis);
    t = max(t, r * tanGamma - h);
    radius = max(radius, length(d));
    rho = max(rho, r);
  }
  float e = 2.0 * pc.pointError + 16.0 * kU * (2.0 * maxAbs + length(centre) + radius + abs(t));
  t += (1.0 + tanGamma) * e * 1.01;
  apex = centre - t * cone.axis;
  maxRadius = (rho + e) * (1.0 + 4.0 * kU);
  if (!isFiniteF(apex) || !isFiniteF(maxRadius) || !isFiniteF(tanGamma)) {
    cone = invalidCone(kVerdictNonFinite);
    apex = vec3(0.0);
    maxRadius = 0.0;
  }
}

// The displaced kernels' layout (shaders/cull/displaced_bound.glsl), as
// frame::packDisplacedPatches packs host cones: (Dmin, Dmax, cos α, sin α), (axis, 1 with a
// cone, 0 without). cosAngle is a lower bound of cos(asin(sinAngle)) within 6u of it, far
// inside the kernel's kDeltaSlack (1e-5), which covers the host's rounding the same way.
void writeDisplaced(uint p, DirCone cone) {
  cones[kConeVec4s * p] = vec4(ranges[p], cone.valid ? cone.cosAngle : 1.0,
                               cone.valid ? cone.sinAngle : 0.0);
  cones[kConeVec4s * p + 1u] = vec4(cone.axis, cone.valid ? 1.0 : 0.0);
  cones[kConeVec4s * p + 2u] = vec4(0.0);
  cones[kConeVec4s * p + 3u] = vec4(0.0);
}

// The layout of cull_layout.h (kConeVec4s), as CullPass packs host cones.
void writeCone(uint p, DirCone cone, vec3 apex, float maxRadius, vec4 derivatives) {
  cones[kConeVec4s * p] = vec4(apex, cone.valid ? cone.sinAngle : 1.0);
  cones[kConeVec4s * p + 1u] = vec4(cone.axis, cone.valid ? -1.0 : float(cone.reason));
  cones[kConeVec4s * p + 2u] = derivatives;
  cones[kConeVec4s * p + 3u] = vec4(maxRadius, cone.valid ? coneAngle(cone) : 0.0, 0.0, 0.0);
}
#endif
