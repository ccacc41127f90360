// The boundary curve of each patch edge, in the order of gl_TessLevelOuter:
// edge 0 is u=0 (parameter v), 1 is v=0 (parameter u), 2 is u=1 (v), 3 is v=1 (u).
// Each row lists the four control points of the edge's cubic Bezier curve, from the
// domain corner with parameter 0 to the one with parameter 1.
#ifndef OSD_CULL_EDGE_CURVES_GLSL
#define OSD_CULL_EDGE_CURVES_GLSL

// Bezier point (i, j) is 4j + i (u fastest).
const int kEdgeCurveBezier[16] =
    int[16](0, 4, 8, 12,  0, 1, 2, 3,  3, 7, 11, 15,  12, 13, 14, 15);
// OpenSubdiv Gregory basis: corner c holds P, Ep, Em, Fp, Fm at 5c + 0..4; corners
// (0,0), (1,0), (1,1), (0,1). The boundary curves use P, Ep and Em (see
// Osd_EvalBasisGregory's boundaryGregory table).
const int kEdgeCurveGregory[16] =
    int[16](0, 2, 16, 15,  0, 1, 7, 5,  5, 6, 12, 10,  15, 17, 11, 10);
#if defined(PATCH_POINTS)
#if PATCH_POINTS == 16
#define kEdgeCurve kEdgeCurveBezier
#else
#define kEdgeCurve kEdgeCurveGregory
#endif
#endif

// Transition bit of Far::PatchParam for each outer edge (bit k: Far edge k).
const uint kEdgeTransitionBit[4] = uint[4](8u, 1u, 2u, 4u);

// True when a's coordinates are lexicographically smaller than b's: picks one direction
// for a shared edge that both neighbours agree on.
bool lexLess(vec3 a, vec3 b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}
#endif
