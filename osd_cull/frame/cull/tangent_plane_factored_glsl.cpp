// The factored tangent-plane coefficients as straight-line GLSL (see the header).
#include "osd_cull/frame/cull/tangent_plane_factored_glsl.h"

#include <map>
#include <string>
#include <vector>

namespace osd_cull::frame {
namespace {

constexpr int kC2[3] = {1, 2, 1};
constexpr int kC3[4] = {1, 3, 3, 1};

std::string idx(int a, int b) { return std::to_string(a) + "_" + std::to_string(b); }
std::string num(int w) { return std::to_string(w) + ".0"; }

}  // namespace

std::string tangentPlaneFactoredGlsl() {
  // No comments: the caller may turn the text into a one-line macro.
  std::string s =
      "uvec4 tangentPlaneFactoredSigns(vec3 b[16], float inputError, float reference,\n"
      "                                float drawn, bvec4 collapsed) {\n";
  // Differences Γ (u) and Δ (v) with (|x|_1, x != 0).
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) {
      const std::string n = idx(i, j);
      s += "  vec3 ga" + n + " = b[" + std::to_string(4 * j + i + 1) + "] - b[" +
           std::to_string(4 * j + i) + "];\n";
      s += "  vec2 gn" + n + " = vec2(l1(ga" + n + "), ga" + n + " != vec3(0.0) ? 1.0 : 0.0);\n";
    }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) {
      const std::string n = idx(i, j);
      s += "  vec3 de" + n + " = b[" + std::to_string(4 * j + 4 + i) + "] - b[" +
           std::to_string(4 * j + i) + "];\n";
      s += "  vec2 dn" + n + " = vec2(l1(de" + n + "), de" + n + " != vec3(0.0) ? 1.0 : 0.0);\n";
    }
  s += "  const float six = 6.0 * inputError;\n";
  // N' = Γ × Δ per (a, c), its bounds and margins.
  for (int a = 0; a < 6; ++a)
    for (int c = 0; c < 6; ++c) {
      std::string value, bound;
      for (int i1 = 0; i1 < 3; ++i1)
        for (int i2 = 0; i2 < 4; ++i2)
          for (int j1 = 0; j1 < 4; ++j1)
            for (int j2 = 0; j2 < 3; ++j2) {
              if (i1 + i2 != a || j1 + j2 != c) continue;
              const std::string w = num(kC2[i1] * kC3[i2] * kC3[j1] * kC2[j2]);
              const std::string g = idx(i1, j1), d = idx(i2, j2);
              value += (value.empty() ? "" : " + ") + w + " * cross(ga" + g + ", de" + d + ")";
              bound += std::string(bound.empty() ? "" : " + ") + w + " * vec2(gn" + g + ".x * dn" +
                       d + ".x, gn" + g + ".y * (dn" + d + ".x + six * dn" + d + ".y) + gn" + g +
                       ".x * dn" + d + ".y)";
            }
      const std::string n = idx(a, c);
      s += "  vec3 n" + n + " = " + value + ";\n";
      s += "  vec2 nb" + n + " = " + bound + ";\n";
      s += "  vec2 nm" + n + " = vec2(kTpArithmeticMargin * nb" + n + ".x + six * nb" + n +
           ".y, inputError * nb" + n + ".x);\n";
    }
  // E - A and its max norm (plus the input error).
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) {
      const std::string n = idx(i, j);
      s += "  vec3 q" + n + " = pc.eye.xyz - b[" + std::to_string(4 * j + i) + "];\n";
      s += "  float qm" + n + " = maxAbs(q" + n + ") + inputError;\n";
    }
  // G' = (E - A) · N' per (p, q) with its margin.
  for (int p = 0; p < 8; ++p)
    for (int q = 0; q < 9; ++q) {
      std::string value, margin;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) {
          const int a = p - i, c = q - j;
          if (a < 0 || a > 5 || c < 0 || c > 5) continue;
          const std::string w = num(kC2[i] * kC3[j]), e = idx(i, j), n = idx(a, c);
          value += (value.empty() ? "" : " + ") + w + " * dot(q" + e + ", n" + n + ")";
          margin += (margin.empty() ? "" : " + ") + w + " * (qm" + e + " * nm" + n + ".x + nm" + n +
                    ".y)";
        }
      s += "  float g" + idx(p, q) + " = " + value + ";\n";
      s += "  float m" + idx(p, q) + " = " + margin + ";\n";
    }
  // v-degree 8 -> 7 from both ends, then the sign counts.
  s += "  uvec4 counts = uvec4(0u);\n";
  for (int p = 0; p < 8; ++p) {
    auto d = [&](int q) { return "d" + idx(p, q); };
    auto m = [&](int q) { return "r" + idx(p, q); };
    s += "  float " + d(0) + " = g" + idx(p, 0) + ", " + m(0) + " = m" + idx(p, 0) + ";\n";
    for (int q = 1; q < 4; ++q)
      s += "  float " + d(q) + " = g" + idx(p, q) + " - " + d(q - 1) + ", " + m(q) + " = m" +
           idx(p, q) + " + " + m(q - 1) + ";\n";
    s += "  float " + d(7) + " = g" + idx(p, 8) + ", " + m(7) + " = m" + idx(p, 8) + ";\n";
    for (int q = 6; q >= 4; --q)
      s += "  float " + d(q) + " = g" + idx(p, q + 1) + " - " + d(q + 1) + ", " + m(q) + " = m" +
           idx(p, q + 1) + " + " + m(q + 1) + ";\n";
    for (int q = 0; q < 8; ++q) {
      std::string edge;
      if (q == 0) edge += "collapsed.x || ";
      if (q == 7) edge += "collapsed.y || ";
      if (p == 0) edge += "collapsed.z || ";
      if (p == 7) edge += "collapsed.w || ";
      s += "  counts += tangentPlaneFactoredCount(" + d(q) + ", " + m(q) + ", " +
           std::to_string(p) + ", " + std::to_string(q) + ", reference, drawn, " + edge +
           "false);\n";
    }
  }
  s += "  return counts;\n}\n";
  return s;
}

}  // namespace osd_cull::frame
