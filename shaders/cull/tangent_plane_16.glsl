// Back-patch stage "tangent-plane-16": the parametric tangent-plane test with 16 threads per
// patch, the parallel algorithm of Loop, Niessner, Eisenacher section 6. Thread (r, c) =
// (lane / 4, lane % 4) owns the four coefficients (r, c), (r, c+4), (r+4, c), (r+4, c+4) of
// the 8x8 array, so no two threads write the same coefficient and each keeps its four sums
// in registers; the table (cull_layout.h kCullBindingTable) is in the section 6 order (entry
// slot * 16 + lane, padded with weight-0 terms to 33 slots), so every thread runs the loop
//   for (k = lane; k < kTangentPlaneTermCount; k += 16)
// Each thread first prepares one control point in shared memory; the sign counts of the 64
// coefficients are then reduced over the 16 threads through shared memory. Same
// arithmetic, rounding rule, skipped terms and Pcnt rule as tangent_plane.glsl.
//
// Must be called by every invocation of the workgroup (it contains barriers).
#include "tangent_plane_common.glsl"

const uint kPatchesPerGroupTp16 = kCullGroupSize / 16u;

shared vec3 sPointB[kCullGroupSize];
shared vec3 sPointQ[kCullGroupSize];
shared vec3 sPointMags[kCullGroupSize];
shared uint sCounts[kCullGroupSize];  // per lane: pcnt | ncnt << 8 | non-finite << 16 |
                                      // pcntDrawn << 17
shared float sDrawnMargin[kPatchesPerGroupTp16];

TangentPlanePoint sharedPoint(uint index) {
  TangentPlanePoint p;
  p.b = sPointB[index];
  p.q = sPointQ[index];
  p.mags = sPointMags[index];
  return p;
}

uint backPatchVerdict(uint patchIndex, uint lane, uint slot, bool run) {
  const bool load = run && isBezier(patchIndex);
  const bool accumulate = load && pc.eye.w != 0.0 && isFiniteF(pc.eye.xyz);
  const uint base = slot * 16u;
  bool finite = matrixIsFinite();
  if (load) {
    vec3 b = controlPoint(firstPoint(patchIndex) + lane);
    finite = finite && isFiniteF(b);
    TangentPlanePoint p = tangentPlanePoint(b);
    sPointB[base + lane] = p.b;
    sPointQ[base + lane] = p.q;
    sPointMags[base + lane] = p.mags;
  }
  // Lane 0 computes the drawn-triangle margin of its patch (0 without CULL_DRAWN).
  if (lane == 0u) sDrawnMargin[slot] = accumulate ? tangentPlaneDrawnMargin(patchIndex) : 0.0;
  memoryBarrierShared();
  barrier();
  const float drawnMargin = sDrawnMargin[slot];
  uvec4 counts = uvec4(0u);
  if (accumulate) {
    vec4 sums[4] = vec4[4](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
    for (uint k = lane; k < kTangentPlaneTermCount; k += 16u) {
      uvec4 t = tangentPlaneTerm(k);
      uint j = base + t.y, kk = base + t.z, l = base + t.w;
      if (sPointB[j] == sPointB[kk] || sPointB[kk] == sPointB[l] || sPointB[j] == sPointB[l])
        continue;
      uint own = 2u * (t.x / 32u) + (t.x % 8u) / 4u;  // which of this thread's four sums
      addTangentPlaneTerm(sums[own], tangentPlaneWeight(k), sharedPoint(j), sharedPoint(kk),
                          sharedPoint(l));
    }
    for (uint i = 0u; i < 4u; ++i) counts += tangentPlaneCounts(sums[i], drawnMargin);
  }
  sCounts[base + lane] = counts.x | (counts.y << 8u) |
                         ((finite && counts.z == 0u) ? 0u : 1u << 16u) | (counts.w << 17u);
  memoryBarrierShared();
  barrier();
  if (!run) return 0xFFu;
  if (!isBezier(patchIndex)) return coneVerdict(patchIndex);
  uint pcnt = 0u, ncnt = 0u, pcntDrawn = 0u;
  bool allFinite = true;
  for (uint i = 0u; i < 16u; ++i) {
    uint v = sCounts[base + i];
    pcnt += v & 0xFFu;
    ncnt += (v >> 8u) & 0xFFu;
    allFinite = allFinite && ((v >> 16u) & 1u) == 0u;
    pcntDrawn += v >> 17u;
  }
  if (!allFinite) return kVerdictNonFinite;
  if (pc.eye.w == 0.0) return kVerdictNoFiniteEye;
  if (!isFiniteF(pc.eye.xyz)) return kVerdictNonFinite;
  return classifyTangentPlane(true, pcnt, ncnt, pcntDrawn);
}
