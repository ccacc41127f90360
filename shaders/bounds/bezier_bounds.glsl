// Bounds of a 16-point bicubic Bezier patch (point (i, j) at 4j + i): TCONE, NCONE (Loop,
// Niessner, Eisenacher §2: Sederberg-Meyers and Shirman-Abi-Ezzi) and the drawn-triangle
// bound's G, H, max |coordinate| and min |Bu x Bv| (bound/drawn_triangles.h), each an upper
// (lower for min |N|) bound of its double reference in cone_of_normals.cpp and
// drawn_triangles.cpp.
#ifndef OSD_CULL_BOUNDS_BEZIER_GLSL
#define OSD_CULL_BOUNDS_BEZIER_GLSL
#include "bounds_common.glsl"

vec3 b(int i, int j) { return pointAt(uint(4 * j + i)); }

// bound::bezierDerivativeBounds: G = max 3 |Δb|, H = max(6 |Δ²b|, 9 |Δu Δv b|). A second
// difference of device points is off by 4 sqrt(3) pc.pointError and rounds by 16u of the
// coordinates.
vec3 derivativeBounds() {
  float maxAbs = 0.0;
  [[dont_unroll]] for (uint k = 0u; k < 16u; ++k) {
    vec3 p = pointAt(k);
    maxAbs = max(maxAbs, max(abs(p.x), max(abs(p.y), abs(p.z))));
  }
  float d1 = 0.0, d2 = 0.0, d11 = 0.0;
  [[dont_unroll]] for (int j = 0; j < 4; ++j)
    [[dont_unroll]] for (int i = 0; i < 3; ++i) {
      d1 = max(d1, length(b(i + 1, j) - b(i, j)));
      d1 = max(d1, length(b(j, i + 1) - b(j, i)));
    }
  [[dont_unroll]] for (int j = 0; j < 4; ++j)
    [[dont_unroll]] for (int i = 0; i < 2; ++i) {
      d2 = max(d2, length(b(i + 2, j) - 2.0 * b(i + 1, j) + b(i, j)));
      d2 = max(d2, length(b(j, i + 2) - 2.0 * b(j, i + 1) + b(j, i)));
    }
  [[dont_unroll]] for (int j = 0; j < 3; ++j)
    [[dont_unroll]] for (int i = 0; i < 3; ++i)
      d11 = max(d11, length(b(i + 1, j + 1) - b(i, j + 1) - b(i + 1, j) + b(i, j)));
  float e1 = 3.5 * pc.pointError + 4.0 * kU * maxAbs;
  float e2 = 7.0 * pc.pointError + 32.0 * kU * maxAbs;
  float g = 3.0 * (d1 + e1) * (1.0 + 8.0 * kU);
  float h = max(6.0 * (d2 + e2), 9.0 * (d11 + e2)) * (1.0 + 8.0 * kU);
  return vec3(g, h, (maxAbs + pc.pointError) * (1.0 + 2.0 * kU));
}

// TCONE: the cones of the 12 tangent (Bu) and 12 bitangent (Bv) control vectors combined.
// minNormal: bound::tangentConesMinNormal with the angles rounded outward.
DirCone tangentCone(out float minNormal) {
  gCount = 0u;
  [[dont_unroll]] for (int j = 0; j < 4; ++j)
    [[dont_unroll]] for (int i = 0; i < 3; ++i) {
      vec3 v = b(i + 1, j) - b(i, j);
      addVector(v, differenceError(v));
    }
  DirCone cu = boundDirections();
  float mu = 3.0e38;
  [[dont_unroll]] for (uint k = 0u; k < gCount; ++k)
    mu = min(mu, dot(vecAt(k), cu.axis) - (errAt(k) + 8.0 * kU * length(vecAt(k))) * 1.01);
  gCount = 0u;
  [[dont_unroll]] for (int j = 0; j < 4; ++j)
    [[dont_unroll]] for (int i = 0; i < 3; ++i) {
      vec3 v = b(j, i + 1) - b(j, i);
      addVector(v, differenceError(v));
    }
  DirCone cv = boundDirections();
  float mv = 3.0e38;
  [[dont_unroll]] for (uint k = 0u; k < gCount; ++k)
    mv = min(mv, dot(vecAt(k), cv.axis) - (errAt(k) + 8.0 * kU * length(vecAt(k))) * 1.01);
  DirCone cone = combineTangentCones(cu, cv);
  minNormal = 0.0;
  if (cone.valid) {
    // Angles between the axes and of the two cones, rounded outward.
    float theta = atan(length(cross(cu.axis, cv.axis)), dot(cu.axis, cv.axis));
    float thetaLo = theta * (1.0 - kTrigSlack) - 16.0 * kU;
    float thetaHi = theta * (1.0 + kTrigSlack) + 16.0 * kU;
    float spread = coneAngle(cu) + coneAngle(cv);
    float low = thetaLo - spread, high = thetaHi + spread;
    mu *= 1.0 - 8.0 * kU;
    mv *= 1.0 - 8.0 * kU;
    if (mu > 0.0 && mv > 0.0 && low > 0.0 && high < 3.14159 * (1.0 - kTrigSlack)) {
      float sinMin = min(sin(low), sin(high)) - 2.0 * kSinAbsError;
      if (sinMin > 0.0) minNormal = 9.0 * mu * mv * sinMin * (1.0 - 16.0 * kU);
    }
  }
  return cone;
}

// NCONE: the 36 coefficients of the bidegree (5,5) normal patch N = Bu x Bv
// (bound::normalPatch), each with the bound of its error: per product term
// w ((|du| + e_du)(|dv| + e_dv) - |du| |dv|) from the inputs, and 64u w (|du| + e_du)
// (|dv| + e_dv) for the cross product, the weights and the sum of at most 16 terms.
// C(2, i), C(3, i), C(5, i) without constant arrays (see the comment on the shared scratch
// of bounds_common.glsl).
float binomial2(int i) { return i == 1 ? 2.0 : 1.0; }
float binomial3(int i) { return i == 1 || i == 2 ? 3.0 : 1.0; }
float binomial5(int i) { return i == 0 || i == 5 ? 1.0 : (i == 1 || i == 4 ? 5.0 : 10.0); }

DirCone normalCone(out float minNormal) {
  // Slots 0-35: the coefficients; 48-59: the 12 scaled bitangent differences.
  [[dont_unroll]] for (int l = 0; l < 3; ++l)
    [[dont_unroll]] for (int k = 0; k < 4; ++k) {
      vec3 d = b(k, l + 1) - b(k, l);
      setVector(48u + uint(4 * l + k), 3.0 * d, 3.0 * differenceError(d) * (1.0 + 2.0 * kU));
    }
  [[dont_unroll]] for (uint k = 0u; k < 36u; ++k) setVector(k, vec3(0.0), 0.0);
  gCount = 36u;
  [[dont_unroll]] for (int j = 0; j < 4; ++j)
    [[dont_unroll]] for (int i = 0; i < 3; ++i) {
      vec3 d = b(i + 1, j) - b(i, j);
      vec3 du = 3.0 * d;
      float eu = 3.0 * differenceError(d) * (1.0 + 2.0 * kU);
      float lu = length(du);
      [[dont_unroll]] for (int l = 0; l < 3; ++l)
        [[dont_unroll]] for (int k = 0; k < 4; ++k) {
          vec3 dv = vecAt(48u + uint(4 * l + k));
          float ev = errAt(48u + uint(4 * l + k)), lv = length(dv);
          int p = i + k, q = j + l;
          float w = (binomial2(i) * binomial3(k) / binomial5(p)) *
                    (binomial3(j) * binomial2(l) / binomial5(q));
          uint slot = uint(6 * q + p);
          setVector(slot, vecAt(slot) + w * cross(du, dv),
                    errAt(slot) + w * (lu * ev + eu * lv + eu * ev) +
                        64.0 * kU * w * (lu + eu) * (lv + ev));
        }
    }
  [[dont_unroll]] for (uint k = 0u; k < 36u; ++k) setVector(k, vecAt(k), errAt(k) * (1.0 + 16.0 * kU));
  DirCone cone = boundDirections();
  minNormal = 0.0;
  if (cone.valid) {
    // N(u,v) is a convex combination of the coefficients: N . a >= min (n_k . a - e_k).
    float m = 3.0e38;
    [[dont_unroll]] for (int k = 0; k < 36; ++k)
      m = min(m, dot(vecAt(k), cone.axis) - (errAt(k) + 8.0 * kU * length(vecAt(k))) * 1.01);
    minNormal = max(0.0, m * (1.0 - 16.0 * kU));
  }
  return cone;
}
#endif
