// Back-patch stage "tangent-plane-16": the parametric tangent-plane test with 16 threads per
// patch, the parallel algorithm of Loop, Niessner, Eisenacher section 6. Thread (r, c) =
// (lane / 4, lane % 4) owns the four control planes (r, c), (r, c+4), (r+4, c), (r+4, c+4) of
// the 8x8 array, so no two threads write the same plane and each keeps its four sums in
// registers; the table (cull_layout.h kCullBindingTable) is in the section 6 order (entry
// slot * 16 + lane, padded with weight-0 terms to 33 slots), so every thread runs the loop
//   for (k = lane; k < kTangentPlaneTermCount; k += 16)
// Each thread first transforms one control point to clip space into shared memory; the
// sign counts of the 64 planes are then reduced over the 16 threads through shared memory.
// Same rounding rule, skipped terms and Pcnt rule as tangent_plane.glsl.
//
// Must be called by every invocation of the workgroup (it contains barriers).
#include "tangent_plane_common.glsl"

shared vec3 sPoint[kCullGroupSize];
shared vec4 sClip[kCullGroupSize];
shared vec4 sAbs[kCullGroupSize];
shared uint sCounts[kCullGroupSize];  // per lane: pcnt | ncnt << 8 | non-finite << 16

uint backPatchVerdict(uint patchIndex, uint lane, uint slot, bool run) {
  const bool load = run && isBezier(patchIndex);
  const bool accumulate = load && pc.eye.w != 0.0;
  const uint base = slot * 16u;
  bool finite = matrixIsFinite();
  if (load) {
    vec3 p = controlPoint(firstPoint(patchIndex) + lane);
    sPoint[base + lane] = p;
    sClip[base + lane] = clipPoint(p);
    sAbs[base + lane] = absClipPoint(p);
    finite = finite && isFiniteF(p);
  }
  memoryBarrierShared();
  barrier();
  uvec2 counts = uvec2(0u);
  if (accumulate) {
    float z[4] = float[4](0.0, 0.0, 0.0, 0.0);
    float bound[4] = float[4](0.0, 0.0, 0.0, 0.0);
    for (uint k = lane; k < kTangentPlaneTermCount; k += 16u) {
      uvec4 t = tangentPlaneTerm(k);
      uint j = base + t.y, kk = base + t.z, l = base + t.w;
      if (sPoint[j] == sPoint[kk] || sPoint[kk] == sPoint[l] || sPoint[j] == sPoint[l]) continue;
      uint own = 2u * (t.x / 32u) + (t.x % 8u) / 4u;  // which of this thread's four planes
      float w = tangentPlaneWeight(k);
      z[own] += w * cross4Z(sClip[j], sClip[kk], sClip[l]);
      bound[own] += abs(w) * cross4ZBound(sAbs[j], sAbs[kk], sAbs[l]);
    }
    for (uint i = 0u; i < 4u; ++i) {
      finite = finite && isFiniteF(z[i]) && isFiniteF(bound[i]);
      counts += planeSignCounts(z[i], bound[i]);
    }
  }
  sCounts[base + lane] = counts.x | (counts.y << 8u) | (finite ? 0u : 1u << 16u);
  memoryBarrierShared();
  barrier();
  if (!run) return 0xFFu;
  if (!isBezier(patchIndex)) return coneVerdict(patchIndex);
  uint pcnt = 0u, ncnt = 0u;
  bool allFinite = true;
  for (uint i = 0u; i < 16u; ++i) {
    uint v = sCounts[base + i];
    pcnt += v & 0xFFu;
    ncnt += (v >> 8u) & 0xFFu;
    allFinite = allFinite && (v >> 16u) == 0u;
  }
  if (!allFinite) return kVerdictNonFinite;
  if (pc.eye.w == 0.0) return kVerdictNoFiniteEye;
  return classifyTangentPlane(true, pcnt, ncnt);
}
