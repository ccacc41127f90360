#version 450
// The cluster test (Zachmann, "Clustered Backface Culling" and "Hierarchical Clustered
// Backface Culling"): one invocation per cluster of osd_cull/bound/patch_clusters.h, the fp32
// mirror of bound::testCluster. A cluster outside a frustum plane or with the eye in its cull
// region writes its members' result codes (culled); one inside the frustum and front-facing
// writes them kept and appends them to the draw list; the rest list their members in
// clusterWork for the per-patch kernel (cull_main.glsl with CULL_CLUSTERS), whose indirect
// dispatch size they raise to cover the list. Margins: 4 kCullRelativeMargin of the
// magnitudes, so every decision is one of the double reference (shared/cull_layout.h).
#include <shared/cluster_layout.h>
#include <shared/cull_layout.h>

layout(local_size_x = kClusterGroupSize) in;

layout(push_constant) uniform Push { CullConstants pc; };
layout(std430, set = 0, binding = kCullBindingResults) writeonly buffer Results { uint results[]; };
layout(std430, set = 0, binding = kCullBindingDrawList) writeonly buffer DrawList {
  uint drawList[];
};
layout(std430, set = 0, binding = kCullBindingCounters) buffer Counters { uint counters[]; };
layout(std430, set = 0, binding = kCullBindingClusterWork) buffer Work { uint clusterWork[]; };
layout(std430, set = 0, binding = kCullBindingClusters) readonly buffer Clusters {
  vec4 clusters[];
};
layout(std430, set = 0, binding = kCullBindingClusterMembers) readonly buffer Members {
  uint clusterMembers[];
};

bool finite3(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

const uint kUndecided = 0u, kCulledFrustum = 1u, kCulledBack = 2u, kAccepted = 3u;

// bound::testCluster: the verdict, and with kCulledFrustum the plane in `plane`.
uint clusterVerdict(uint k, uint flags, out uint plane) {
  plane = kFrustumInside;
  const vec4 v0 = clusters[kClusterVec4s * k], v1 = clusters[kClusterVec4s * k + 1u];
  const vec4 v2 = clusters[kClusterVec4s * k + 2u], v3 = clusters[kClusterVec4s * k + 3u];
  const vec3 c = 0.5 * (v0.xyz + v1.xyz), e = 0.5 * (v1.xyz - v0.xyz);
  const float eps = 4.0 * kCullRelativeMargin;
  if (!finite3(c) || !finite3(e)) return kUndecided;
  bool inside = true;
  if ((flags & kClusterFlagFrustum) != 0u) {
    const mat4 m = pc.viewProjection;
    const vec4 rx = vec4(m[0].x, m[1].x, m[2].x, m[3].x), ry = vec4(m[0].y, m[1].y, m[2].y, m[3].y);
    const vec4 rz = vec4(m[0].z, m[1].z, m[2].z, m[3].z), rw = vec4(m[0].w, m[1].w, m[2].w, m[3].w);
    const vec4 planes[6] = vec4[6](rw + rx, rw - rx, rw + ry, rw - ry, rz, rw - rz);
    const vec4 ca = vec4(abs(c) + e, 1.0);
    const float mx = dot(abs(rx), ca), my = dot(abs(ry), ca), mz = dot(abs(rz), ca),
                mw = dot(abs(rw), ca);
    const float mags[6] = float[6](mw + mx, mw + mx, mw + my, mw + my, mz, mw + mz);
    for (uint p = 0u; p < 6u; ++p) {
      const vec4 q = planes[p];
      const float mid = dot(q.xyz, c) + q.w, spread = dot(abs(q.xyz), e);
      const float margin = eps * mags[p];
      if (!finite3(vec3(mid, spread, margin))) return kUndecided;
      if (mid + spread < -margin) {
        plane = p;
        return kCulledFrustum;
      }
      if (!(mid - spread > margin)) inside = false;
    }
  }
  bool front = (flags & kClusterFlagBackPatch) == 0u;
  const vec3 eye = pc.eye.xyz;
  if ((flags & kClusterFlagBackPatch) != 0u && v2.w != 0.0 && pc.eye.w != 0.0 && finite3(eye)) {
    const vec3 axis = v3.xyz;
    if ((flags & kClusterFlagBackCull) != 0u) {
      const vec3 d = eye - v2.xyz;
      const float lhs = dot(axis, d) + v1.w * length(d);
      if (lhs < -eps * (length(eye) + length(v2.xyz))) return kCulledBack;
    }
    // Front-facing from every corner (the test is concave in the point: the corners decide).
    front = true;
    for (uint k = 0u; k < 8u && front; ++k) {
      const vec3 p = vec3((k & 1u) != 0u ? v1.x : v0.x, (k & 2u) != 0u ? v1.y : v0.y,
                          (k & 4u) != 0u ? v1.z : v0.z);
      const vec3 d = eye - p;
      front = dot(axis, d) - v0.w * length(d) > eps * (length(eye) + length(p));
    }
  }
  if ((flags & kClusterFlagAccept) != 0u && inside && front) return kAccepted;
  return kUndecided;
}

void main() {
  const uint k = gl_GlobalInvocationID.x;
  if (k >= clusterWork[kClusterWorkClusters]) return;
  const uint flags = clusterWork[kClusterWorkFlags];
  const uvec4 range = uvec4(clusterMembers[4u * k], clusterMembers[4u * k + 1u],
                            clusterMembers[4u * k + 2u], clusterMembers[4u * k + 3u]);
  const uint first = 4u * clusterWork[kClusterWorkClusters] + range.x;
  const uint count = range.y + range.z;
  uint plane;
  const uint verdict = clusterVerdict(k, flags, plane);
  if (verdict == kUndecided) {
    atomicAdd(clusterWork[kClusterWorkUndecided], 1u);
    const uint at = atomicAdd(clusterWork[kClusterWorkListed], count);
    for (uint i = 0u; i < count; ++i)
      clusterWork[kClusterWorkHeader + at + i] = clusterMembers[first + i];
    const uint perGroup = clusterWork[kClusterWorkPatchesPerGroup];
    atomicMax(clusterWork[0], (at + count + perGroup - 1u) / perGroup);
    return;
  }
  uint code = kResultInitial;
  if (verdict == kCulledFrustum) {
    code = (code & ~(0xFu << kResultShiftFrustum)) | (plane << kResultShiftFrustum);
    code = (code & ~0xFu) | kStageFrustum;
  } else if (verdict == kCulledBack) {
    code = (code & ~(0xFFu << kResultShiftBackPatch)) | (kVerdictBackFacing << kResultShiftBackPatch);
    code = (code & ~0xFu) | kStageBackPatch;
  } else {
    if ((flags & kClusterFlagFrustum) != 0u)
      code = (code & ~(0xFu << kResultShiftFrustum)) | (kFrustumInside << kResultShiftFrustum);
    if ((flags & kClusterFlagBackPatch) != 0u)
      code = (code & ~(0xFFu << kResultShiftBackPatch)) |
             (kVerdictFrontFacing << kResultShiftBackPatch);
  }
  const bool accepted = verdict == kAccepted;
  code |= (accepted ? kResultClusterAccepted : kResultClusterCulled) << kResultShiftCluster;
  atomicAdd(clusterWork[accepted ? kClusterWorkAccepted : kClusterWorkCulled], 1u);
  for (uint i = 0u; i < count; ++i) results[clusterMembers[first + i]] = code;
  if (!accepted) return;
  const uint b = range.y > 0u ? atomicAdd(counters[kCounterSurvivorsBezier], range.y) : 0u;
  const uint g = range.z > 0u ? atomicAdd(counters[kCounterSurvivorsGregory], range.z) : 0u;
  for (uint i = 0u; i < range.y; ++i) drawList[b + i] = clusterMembers[first + i];
  for (uint i = 0u; i < range.z; ++i)
    drawList[pc.bezierCount + g + i] = clusterMembers[first + range.y + i];
}
