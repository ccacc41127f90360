#include "osd_cull/bound/tangent_plane_table.h"

#include "osd_cull/error.h"

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <string>
#include <tuple>
#include <vector>

namespace osd_cull::bound {
namespace {

// Exact rational arithmetic on int64 with overflow checks; the derivation's numbers stay
// far below 2^63, and an overflow would throw rather than produce a wrong table.
struct Rational {
  int64_t num = 0;
  int64_t den = 1;

  static int64_t checked(bool overflow, int64_t value) {
    if (overflow)
      throw Error(std::string(__FILE__) + ": tangent-plane table derivation overflowed");
    return value;
  }
  static Rational make(int64_t n, int64_t d) {
    if (d < 0) n = -n, d = -d;
    const int64_t g = std::gcd(n < 0 ? -n : n, d);
    return g > 1 ? Rational{n / g, d / g} : Rational{n, d};
  }
  friend Rational operator*(Rational a, Rational b) {
    int64_t n, d;
    const bool o1 = __builtin_mul_overflow(a.num, b.num, &n);
    const bool o2 = __builtin_mul_overflow(a.den, b.den, &d);
    return make(checked(o1, n), checked(o2, d));
  }
  friend Rational operator+(Rational a, Rational b) {
    const int64_t g = std::gcd(a.den, b.den);
    int64_t x, y, n, d;
    const bool o1 = __builtin_mul_overflow(a.num, b.den / g, &x);
    const bool o2 = __builtin_mul_overflow(b.num, a.den / g, &y);
    const bool o3 = __builtin_add_overflow(checked(o1, x), checked(o2, y), &n);
    const bool o4 = __builtin_mul_overflow(a.den / g, b.den, &d);
    return make(checked(o3, n), checked(o4, d));
  }
  friend Rational operator-(Rational a, Rational b) { return a + Rational{-b.num, b.den}; }
  friend Rational operator/(Rational a, Rational b) { return a * make(b.den, b.num); }
  bool isZero() const { return num == 0; }
};

int64_t binomial(int n, int k) {
  int64_t r = 1;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

// A univariate polynomial in Bernstein form of the given degree.
struct Bernstein {
  int degree = 0;
  std::vector<Rational> c;
};

Bernstein basis3(int i) {
  Bernstein b{3, std::vector<Rational>(4)};
  b.c[i] = {1, 1};
  return b;
}

// d/dt B^3_i = 3 (B^2_{i-1} - B^2_i).
Bernstein derivative3(int i) {
  Bernstein b{2, std::vector<Rational>(3)};
  if (i >= 1) b.c[i - 1] = b.c[i - 1] + Rational{3, 1};
  if (i <= 2) b.c[i] = b.c[i] - Rational{3, 1};
  return b;
}

// B^m_i B^n_j = C(m,i) C(n,j) / C(m+n,i+j) B^{m+n}_{i+j}.
Bernstein multiply(const Bernstein& a, const Bernstein& b) {
  Bernstein r{a.degree + b.degree, std::vector<Rational>(a.degree + b.degree + 1)};
  for (int i = 0; i <= a.degree; ++i)
    for (int j = 0; j <= b.degree; ++j) {
      if (a.c[i].isZero() || b.c[j].isZero()) continue;
      const Rational w =
          Rational::make(binomial(a.degree, i) * binomial(b.degree, j), binomial(r.degree, i + j));
      r.c[i + j] = r.c[i + j] + a.c[i] * b.c[j] * w;
    }
  return r;
}

// Exact degree reduction 8 -> 7 of a polynomial that is of degree 7: inverts degree
// elevation c8_i = (i/8) c7_{i-1} + (1 - i/8) c7_i from the left and checks c8_8 = c7_7.
std::array<Rational, 8> reduceDegree(const std::array<Rational, 9>& c8) {
  std::array<Rational, 8> c7;
  c7[0] = c8[0];
  for (int i = 1; i <= 7; ++i)
    c7[i] = (c8[i] - Rational::make(i, 8) * c7[i - 1]) / Rational::make(8 - i, 8);
  const Rational rest = c8[8] - c7[7];
  if (!rest.isZero())
    throw Error(std::string(__FILE__) +
                ": the parametric tangent plane is not of bidegree 7 (Loop et al. §3)");
  return c7;
}

using Grid9 = std::array<std::array<Rational, 9>, 9>;  // [v][u], bidegree (8,8)

std::vector<TangentPlaneTerm> derive() {
  // φ_a = B3_i(u) B3_j(v), φu_a = B3_i'(u) B3_j(v), φv_a = B3_i(u) B3_j'(v), a = 4j + i.
  // T = Σ_{a,b,c} φ_a φu_b φv_c cross4(b_a, b_b, b_c); cross4 is alternating, so each
  // sorted triple collects Σ_σ sign(σ) of the products in permuted roles.
  std::map<std::tuple<int, int, int>, Grid9> byTriple;
  for (int a = 0; a < 16; ++a)
    for (int b = 0; b < 16; ++b)
      for (int c = 0; c < 16; ++c) {
        if (a == b || b == c || a == c) continue;
        std::array<int, 3> s{a, b, c};
        // Sign of the permutation that sorts (a, b, c).
        int sign = 1;
        for (int x = 0; x < 3; ++x)
          for (int y = x + 1; y < 3; ++y)
            if (s[x] > s[y]) sign = -sign;
        std::sort(s.begin(), s.end());
        const Bernstein pu = multiply(multiply(basis3(a % 4), derivative3(b % 4)), basis3(c % 4));
        const Bernstein pv = multiply(multiply(basis3(a / 4), basis3(b / 4)), derivative3(c / 4));
        Grid9& g = byTriple[{s[0], s[1], s[2]}];
        for (int q = 0; q <= 8; ++q)
          for (int p = 0; p <= 8; ++p) {
            if (pu.c[p].isZero() || pv.c[q].isZero()) continue;
            const Rational term = pu.c[p] * pv.c[q];
            g[q][p] = sign > 0 ? g[q][p] + term : g[q][p] - term;
          }
      }

  std::vector<TangentPlaneTerm> terms;
  for (const auto& [triple, g] : byTriple) {
    // Reduce u (rows), then v (columns), from bidegree (8,8) to (7,7).
    std::array<std::array<Rational, 8>, 9> rowsReduced;  // [v 0..8][u 0..7]
    for (int q = 0; q <= 8; ++q) rowsReduced[q] = reduceDegree(g[q]);
    for (int p = 0; p < 8; ++p) {
      std::array<Rational, 9> column;
      for (int q = 0; q <= 8; ++q) column[q] = rowsReduced[q][p];
      const std::array<Rational, 8> reduced = reduceDegree(column);
      for (int q = 0; q < 8; ++q) {
        const Rational w = reduced[q];
        if (w.isZero()) continue;
        TangentPlaneTerm t;
        t.target = static_cast<uint32_t>(8 * q + p);
        t.j = static_cast<uint32_t>(std::get<0>(triple));
        t.k = static_cast<uint32_t>(std::get<1>(triple));
        t.l = static_cast<uint32_t>(std::get<2>(triple));
        t.numerator = w.num;
        t.denominator = w.den;
        t.weight = static_cast<double>(w.num) / static_cast<double>(w.den);
        terms.push_back(t);
      }
    }
  }
  std::sort(terms.begin(), terms.end(), [](const TangentPlaneTerm& x, const TangentPlaneTerm& y) {
    return std::tie(x.target, x.j, x.k, x.l) < std::tie(y.target, y.j, y.k, y.l);
  });
  return terms;
}

// §6: thread (r, c) of a 4x4 grid owns targets (r, c), (r, c+4), (r+4, c), (r+4, c+4).
uint32_t ownerThread(uint32_t target) {
  const uint32_t row = target / 8, col = target % 8;
  return 4 * (row % 4) + (col % 4);
}

std::vector<TangentPlaneTerm> interleave(const std::vector<TangentPlaneTerm>& serial) {
  std::array<std::vector<TangentPlaneTerm>, kTangentPlaneThreads> perThread;
  for (const TangentPlaneTerm& t : serial) perThread[ownerThread(t.target)].push_back(t);
  size_t slots = 0;
  for (const auto& list : perThread) slots = std::max(slots, list.size());
  std::vector<TangentPlaneTerm> out(slots * kTangentPlaneThreads);
  for (uint32_t thread = 0; thread < kTangentPlaneThreads; ++thread) {
    const uint32_t firstTarget = 8 * (thread / 4) + thread % 4;
    for (size_t s = 0; s < slots; ++s) {
      TangentPlaneTerm t{firstTarget, 0, 1, 2, 0.0, 0, 1};  // padding: weight 0
      if (s < perThread[thread].size()) t = perThread[thread][s];
      out[s * kTangentPlaneThreads + thread] = t;
    }
  }
  return out;
}

}  // namespace

std::span<const TangentPlaneTerm> tangentPlaneTerms() {
  static const std::vector<TangentPlaneTerm> terms = derive();
  return terms;
}

std::span<const TangentPlaneTerm> tangentPlaneParallelTerms() {
  static const std::vector<TangentPlaneTerm> terms = [] {
    const auto serial = tangentPlaneTerms();
    return interleave({serial.begin(), serial.end()});
  }();
  return terms;
}

std::string tangentPlaneTableGlsl(bool parallelOrder) {
  const auto terms = parallelOrder ? tangentPlaneParallelTerms() : tangentPlaneTerms();
  const std::string n = std::to_string(terms.size());
  std::string out =
      "// Generated by osd_cull::bound::tangentPlaneTableGlsl() from T = cross4(B, Bu, Bv)\n"
      "// (Loop, Niessner, Eisenacher, sections 3, 5" +
      std::string(parallelOrder ? ", 6: entry slot * 16 + thread" : "") + ").\n";
  out += "const uint kTangentPlaneTermCount = " + n + "u;\n";
  out += "const uvec4 kTangentPlaneTerms[" + n + "] = uvec4[](";
  for (size_t i = 0; i < terms.size(); ++i) {
    const TangentPlaneTerm& t = terms[i];
    out += (i % 4 == 0 ? "\n    " : " ") + std::string("uvec4(") + std::to_string(t.target) +
           "u, " + std::to_string(t.j) + "u, " + std::to_string(t.k) + "u, " + std::to_string(t.l) +
           "u)" + (i + 1 < terms.size() ? "," : "");
  }
  out += ");\nconst float kTangentPlaneWeights[" + n + "] = float[](";
  for (size_t i = 0; i < terms.size(); ++i) {
    const TangentPlaneTerm& t = terms[i];
    out += (i % 6 == 0 ? "\n    " : " ") + std::to_string(t.numerator) + ".0 / " +
           std::to_string(t.denominator) + ".0" + (i + 1 < terms.size() ? "," : "");
  }
  out += ");\n";
  return out;
}

}  // namespace osd_cull::bound
