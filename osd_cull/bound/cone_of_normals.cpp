#include "osd_cull/bound/cone_of_normals.h"

#include "osd_cull/bound/clip_space.h"
#include "osd_cull/bound/patch_eval.h"
#include "osd_cull/error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace osd_cull::bound {
namespace {

constexpr double kHalfPi = std::numbers::pi / 2.0;

void requireSize(std::span<const glm::dvec3> points, size_t expected, const char* what) {
  if (points.size() != expected)
    throw Error(std::string(__FILE__) + ": a " + what + " patch has " + std::to_string(expected) +
                " control points, got " + std::to_string(points.size()));
}

// The terms of the angle between unit vectors a and b: |a x b|² and a . b
// (glm::length(v) is std::sqrt(glm::dot(v, v)), so sqrt(s2) is bit for bit |a x b|).
struct AngleTerms {
  double s2, d;
};

AngleTerms angleTerms(const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 c = glm::cross(a, b);
  return {glm::dot(c, c), glm::dot(a, b)};
}

// Angle between unit vectors, accurate near 0 and pi (unlike acos of a dot product).
double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  const AngleTerms t = angleTerms(a, b);
  return std::atan2(std::sqrt(t.s2), t.d);
}

// A cone of directions: every vector it was built from lies within `angle` of `axis`.
struct DirectionCone {
  glm::dvec3 axis{0.0};
  double angle = 0.0;
  bool valid = false;
  BackPatchVerdict reason = BackPatchVerdict::NoNormal;
};

// The largest of atan2(s_i, d_i) + slack_i over the unit vectors (the angle of the widest
// one from `axis`, widened by its uncertainty), and in *farthest the last index that
// reaches it (left as it is when no angle compares >= 0, i.e. all are NaN).
//
// Exhaustive: one atan2 (and one asin for an uncertain direction) per vector, the
// definition. Filtered: the same value and index with atan2 and asin only for the few
// vectors that can be the largest, identified by a key computed with one square root and
// no trigonometry. With θ the angle to the axis (sin θ = sqrt(s2), cos θ = d for
// s2 = |a x u|², d = a . u) and σ the slack (sin σ = e / |v|, cos σ = sqrt(1 - sin²σ)),
// x = θ + σ lies in [0, 3π/2] and the key is
//   k(x) = sin x = sin θ cos σ + cos θ sin σ      where cos x = cos θ cos σ - sin θ sin σ >= 0,
//   k(x) = 2 - sin x                              otherwise,
// increasing on [0, 3π/2] and continuous at π/2. Proof that it keeps every index that can
// be the largest: while cos x >= 0 (so θ <= π/2 and both products are >= 0) the key is a
// sum of non-negative products, within a few ulps *relative* of sin x even for tiny angles;
// beyond, k >= 1 and its absolute error of a few ulps is relative too. The computed angle
// A_i = atan2(..) + asin(..) is within a few ulps (relative error e <= 1e-15) of the exact x_i
// of the computed terms, and |k'| <= 1, k(x) >= 2x/π on [0, π/2], so k(A_i) is within
// (say) 10 e of k(x_i) relatively, and so of the computed key. Let j be an index of the
// largest computed angle and m one of the largest key: A_j >= A_m gives k(A_j) >= k(A_m),
// hence key_j >= key_m (1 - 40 e) > key_m (1 - 1e-9): every index that can reach the largest
// angle (ties included) passes the filter, in the same order, and the vectors filtered out
// have smaller angles and could never be the last to reach it. A NaN key falls back to the
// exhaustive loop. (Before session 14 only vectors without slack were filtered, so NCONE,
// whose 36 coefficients all carry an error bound, took 360 atan2 and 36 asin per patch.)
struct Directions {
  std::vector<double> x, y, z;   // the unit directions, structure of arrays (the key loop)
  std::vector<double> sinSlack;  // e_i / |v_i|, 0 for an exact vector
  std::vector<double> cosSlack;  // sqrt(1 - sinSlack²)
  std::vector<double> slack;     // asin(sinSlack), NaN until needed (filtered search)
  std::vector<double> s2, d, key;
  size_t size() const { return x.size(); }
  glm::dvec3 unit(size_t i) const { return {x[i], y[i], z[i]}; }
};

double slackOf(Directions& dir, size_t i) {
  double& s = dir.slack[i];
  // asin(0) is +0, as the exhaustive loop's.
  if (std::isnan(s)) s = dir.sinSlack[i] == 0.0 ? 0.0 : std::asin(dir.sinSlack[i]);
  return s;
}

// |axis x u|² and axis . u of direction i, as angleTerms() forms them from glm::cross and
// glm::dot (the same products and sums in the same order), on the arrays: one expression
// for both searches, so that they agree bit for bit however the compiler contracts it.
inline void termsOf(double ax, double ay, double az, double x, double y, double z, double* s2,
                    double* d) {
  const double cx = ay * z - y * az, cy = az * x - z * ax, cz = ax * y - x * ay;
  *s2 = cx * cx + cy * cy + cz * cz;
  *d = ax * x + ay * y + az * z;
}

double widestExhaustive(const glm::dvec3& axis, Directions& dir, size_t* farthest) {
  double worst = 0.0;
  for (size_t i = 0; i < dir.size(); ++i) {
    double s2, d;
    termsOf(axis.x, axis.y, axis.z, dir.x[i], dir.y[i], dir.z[i], &s2, &d);
    const double a = std::atan2(std::sqrt(s2), d) + slackOf(dir, i);
    if (a >= worst) worst = a, *farthest = i;
  }
  return worst;
}

constexpr double kPseudoAngleFilter = 1e-9;

// The key of every direction, and the largest key (NaN if any key is not >= 0, NaN
// included): a branch-free loop over arrays that the compiler vectorizes (this file is
// built with -fno-math-errno -fno-trapping-math: sqrt without an errno path, the selects
// if-converted; out of line, where the vectorizer sees plain pointers; cloned for AVX2,
// whose results are the same: no contraction into FMA).
[[gnu::noinline, gnu::target_clones("avx2", "default")]] double directionKeys(
    double ax, double ay, double az, const double* __restrict x, const double* __restrict y,
    const double* __restrict z, const double* __restrict cs, const double* __restrict ss,
    double* __restrict s2, double* __restrict dd, double* __restrict key, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    double s, d;
    termsOf(ax, ay, az, x[i], y[i], z[i], &s, &d);
    const double sinTheta = std::sqrt(s);
    const double sinX = sinTheta * cs[i] + d * ss[i], beyond = 2.0 - sinX;
    const bool within = d * cs[i] - sinTheta * ss[i] >= 0.0;
    s2[i] = s;
    dd[i] = d;
    key[i] = within ? sinX : beyond;
  }
  double top = 0.0;
  size_t bad = 0;  // keys not >= 0 (NaN included)
  for (size_t i = 0; i < n; ++i) {
    top = top < key[i] ? key[i] : top;
    bad += key[i] >= 0.0 ? 0 : 1;
  }
  return bad == 0 ? top : std::numeric_limits<double>::quiet_NaN();
}

double widestFiltered(const glm::dvec3& axis, Directions& dir, size_t* farthest) {
  const size_t n = dir.size();
  const double top = directionKeys(axis.x, axis.y, axis.z, dir.x.data(), dir.y.data(), dir.z.data(),
                                   dir.cosSlack.data(), dir.sinSlack.data(), dir.s2.data(),
                                   dir.d.data(), dir.key.data(), n);
  if (std::isnan(top)) return widestExhaustive(axis, dir, farthest);
  const double *key = dir.key.data(), *s2 = dir.s2.data(), *dd = dir.d.data();
  const double threshold = top * (1.0 - kPseudoAngleFilter);
  double worst = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (key[i] < threshold) continue;
    const double a = std::atan2(std::sqrt(s2[i]), dd[i]) + slackOf(dir, i);
    if (a >= worst) worst = a, *farthest = i;
  }
  return worst;
}

// Bounds the directions of `vectors`, each known up to an absolute error `errors[i]`
// (|computed - exact| <= error): exact zeros are skipped (they add nothing to a
// non-negative combination); a vector not longer than its error has an unknown direction.
// The axis is the better of the normalized mean and a few Badoiu-Clarkson steps toward the
// farthest direction (an approximate minimal enclosing cone).
DirectionCone boundDirections(std::span<const glm::dvec3> vectors, std::span<const double> errors,
                              ConeSearch search) {
  // Scratch buffers of this thread, reused from call to call (no allocation per patch).
  thread_local Directions dir;
  dir.x.clear();
  dir.y.clear();
  dir.z.clear();
  dir.sinSlack.clear();
  for (size_t i = 0; i < vectors.size(); ++i) {
    const double len = glm::length(vectors[i]);
    if (len == 0.0 && errors[i] == 0.0) continue;
    if (!(len > errors[i])) return {glm::dvec3(0.0), 0.0, false, BackPatchVerdict::WideCone};
    // One division: the unit is within an ulp or two of vectors[i] / len, far inside the
    // angle margin; both searches read the same units.
    const double inverse = 1.0 / len;
    const glm::dvec3 unit = vectors[i] * inverse;
    dir.x.push_back(unit.x);
    dir.y.push_back(unit.y);
    dir.z.push_back(unit.z);
    dir.sinSlack.push_back(errors[i] == 0.0 ? 0.0 : errors[i] * inverse);
  }
  if (dir.size() == 0) return {};
  const size_t n = dir.size();
  dir.cosSlack.resize(n);
  for (size_t i = 0; i < n; ++i)
    dir.cosSlack[i] = std::sqrt(1.0 - dir.sinSlack[i] * dir.sinSlack[i]);
  dir.slack.assign(n, std::numeric_limits<double>::quiet_NaN());
  dir.s2.resize(n);
  dir.d.resize(n);
  dir.key.resize(n);
  const bool filtered = search == ConeSearch::Filtered;
  auto widest = [&](const glm::dvec3& axis, size_t* farthest) {
    return filtered ? widestFiltered(axis, dir, farthest) : widestExhaustive(axis, dir, farthest);
  };
  glm::dvec3 sum(0.0);
  for (size_t i = 0; i < n; ++i) sum += dir.unit(i);
  if (!(glm::length(sum) > 0.0)) return {glm::dvec3(0.0), 0.0, false, BackPatchVerdict::WideCone};
  glm::dvec3 axis = glm::normalize(sum);
  size_t far = 0;
  double angle = widest(axis, &far);
  // Badoiu-Clarkson on the tips of the unit vectors: centre += (farthest - centre)/(k+1).
  // The farthest vector from normalize(centre) is the one found for the previous
  // candidate (the same vector, bit for bit), so each step evaluates one direction.
  glm::dvec3 centre = axis;
  size_t f = far;
  // normalize(axis) is axis itself but for an ulp now and then: search again only then.
  if (const glm::dvec3 start = glm::normalize(centre); start != axis) f = 0, widest(start, &f);
  for (int k = 1; k <= 8; ++k) {
    centre += (dir.unit(f) - centre) / static_cast<double>(k + 1);
    if (!(glm::length(centre) > 0.0)) break;
    const glm::dvec3 candidate = glm::normalize(centre);
    f = 0;
    const double a = widest(candidate, &f);
    if (a < angle) angle = a, axis = candidate;
  }
  angle += kConeAngleMargin;
  if (!std::isfinite(angle) || angle >= kHalfPi)
    return {axis, angle, false, BackPatchVerdict::WideCone};
  return {axis, angle, true, BackPatchVerdict::BackFacing};
}

// Places the apex: l = c - t a with the smallest t such that every point P lies within
// 90° - γ of the axis seen from l, i.e. h + t >= ρ tan γ for P - c = h a + r, |r| = ρ.
// The points bound the patch (convex hull), so the whole patch lies in that cone.
ConeOfNormals withApex(const glm::dvec3& axis, double gamma, std::span<const glm::dvec3> points) {
  ConeOfNormals cone;
  glm::dvec3 centre(0.0);
  for (const glm::dvec3& p : points) centre += p;
  centre /= static_cast<double>(points.size());
  const double tanGamma = std::tan(gamma);
  double t = -std::numeric_limits<double>::infinity();
  double radius = 0.0;
  for (const glm::dvec3& p : points) {
    const glm::dvec3 d = p - centre;
    const double h = glm::dot(d, axis);
    const double rho = glm::length(d - h * axis);
    t = std::max(t, rho * tanGamma - h);
    radius = std::max(radius, glm::length(d));
    cone.maxRadius = std::max(cone.maxRadius, rho);
  }
  cone.maxRadius += kRelativeMargin * (radius + glm::length(centre));
  // Rounding of d, h, rho is below a few ulps of |P| + |c|; widen by far more.
  t += kRelativeMargin * (radius + glm::length(centre)) * (1.0 + tanGamma);
  cone.apex = centre - t * axis;
  cone.axis = axis;
  cone.sinAngle = std::sin(gamma);
  cone.angle = gamma;
  cone.valid = std::isfinite(cone.apex.x) && std::isfinite(cone.apex.y) &&
               std::isfinite(cone.apex.z) && std::isfinite(cone.sinAngle);
  cone.reason = cone.valid ? BackPatchVerdict::BackFacing : BackPatchVerdict::NonFinite;
  return cone;
}

ConeOfNormals invalidCone(BackPatchVerdict reason) {
  ConeOfNormals c;
  c.valid = false;
  c.reason = reason;
  return c;
}

// Sederberg and Meyers: tangents within α of a and β of b have unit normals n with
// |n·a| <= sin α and |n·b| <= sin β; writing n = p + z c (c = a x b / |a x b|, p in the
// plane of a and b), the farthest corner of that parallelogram has
// |p|² = (sin²α + 2 sinα sinβ |cos θ| + sin²β) / sin²θ = sin²γ. If it is below 1, t1 and t2
// are never parallel and t1 x t2 stays on the side of c (docs/algorithms/back-patch.md).
ConeOfNormals combineTangentCones(const DirectionCone& tu, const DirectionCone& tv,
                                  std::span<const glm::dvec3> points) {
  if (!tu.valid) return invalidCone(tu.reason);
  if (!tv.valid) return invalidCone(tv.reason);
  const glm::dvec3 c = glm::cross(tu.axis, tv.axis);
  const double sinTheta = glm::length(c);
  const double cosTheta = glm::dot(tu.axis, tv.axis);
  if (!(sinTheta > 0.0)) return invalidCone(BackPatchVerdict::WideCone);
  const double sa = std::sin(tu.angle), sb = std::sin(tv.angle);
  const double sin2 =
      (sa * sa + 2.0 * sa * sb * std::abs(cosTheta) + sb * sb) / (sinTheta * sinTheta);
  if (!(sin2 < 1.0)) return invalidCone(BackPatchVerdict::WideCone);
  const double gamma = std::asin(std::sqrt(sin2)) + kConeAngleMargin;
  if (!(gamma < kHalfPi)) return invalidCone(BackPatchVerdict::WideCone);
  return withApex(c / sinTheta, gamma, points);
}

// A lower bound of |Bu x Bv| for TCONE: Bu = 3 Σ w_k du_k (convex weights) has
// |Bu| >= Bu . a_u >= 3 min du_k . a_u, the same for Bv, and the angle between Bu and Bv lies
// in [θ - α - β, θ + α + β] (θ between the axes), so its sine is at least the smaller sine of
// the two ends when both lie in (0, π).
double tangentConesMinNormal(std::span<const glm::dvec3> du, std::span<const glm::dvec3> dv,
                             const DirectionCone& cu, const DirectionCone& cv) {
  double mu = std::numeric_limits<double>::infinity(), mv = mu, scale = 0.0;
  for (const glm::dvec3& d : du)
    mu = std::min(mu, glm::dot(d, cu.axis)), scale = std::max(scale, glm::length(d));
  for (const glm::dvec3& d : dv)
    mv = std::min(mv, glm::dot(d, cv.axis)), scale = std::max(scale, glm::length(d));
  mu -= kRelativeMargin * scale;
  mv -= kRelativeMargin * scale;
  const double theta = angleBetween(cu.axis, cv.axis);
  const double low = theta - cu.angle - cv.angle, high = theta + cu.angle + cv.angle;
  if (!(mu > 0.0 && mv > 0.0 && low > 0.0 && high < std::numbers::pi)) return 0.0;
  const double sinMin = std::min(std::sin(low), std::sin(high)) - 1e-12;
  return sinMin > 0.0 ? 9.0 * mu * mv * sinMin : 0.0;
}

// The tangent cone of a Gregory patch in one direction. With the Bézier net at (u,v),
//   G_u = 3 Σ B2_i(u) B3_j(v) (q[i+1,j] - q[i,j])  +  Σ_m β_m(u,v) r_m,
// where each q is a convex blend of its candidates, so the first sum divided by 3 is a
// convex combination of the candidate differences d_k, and r_m are the four signed blend
// derivative directions with weights β_m = B_i B_j |a_u b - a b_u| / (a + b)² >= 0. In the
// corner's local coordinates (x, y) every β_m has the form 9 x y (1-x)² (1-y)² y / (x+y)²
// (or with x in place of the last y) <= (9/4) y (1-y)² <= 1/3, so
//   G_u / 3  lies in  conv{d_k} + ball(ρ),  ρ = Σ_m |r_m| / 9.
// Two conservative cones, the narrower one is used:
// (A) if every d_k has component >= h along an axis a with h > ρ, then G_u / 3 has
//     component >= h - ρ along a and <= P + ρ across it (P = max perpendicular part of the
//     d_k), so G_u is within atan((P + ρ) / (h - ρ)) of a;
// (B) G_u is a non-negative combination of the d_k and r_m: the cone of their directions.
DirectionCone gregoryTangentCone(const std::vector<glm::dvec3>& d, const std::vector<glm::dvec3>& r,
                                 ConeSearch search) {
  std::vector<glm::dvec3> all = d;
  all.insert(all.end(), r.begin(), r.end());
  const std::vector<double> zeros(all.size(), 0.0);
  DirectionCone best = boundDirections(all, zeros, search);
  const DirectionCone main =
      boundDirections(d, std::span<const double>(zeros).first(d.size()), search);
  if (!main.valid) return best;
  double rho = 0.0;
  for (const glm::dvec3& v : r) rho += glm::length(v);
  rho = rho / 9.0 * (1.0 + kRelativeMargin);
  double h = std::numeric_limits<double>::infinity(), perp = 0.0, scale = 0.0;
  for (const glm::dvec3& v : d) {
    const double along = glm::dot(v, main.axis);
    h = std::min(h, along);
    perp = std::max(perp, glm::length(v - along * main.axis));
    scale = std::max(scale, glm::length(v));
  }
  // Rounding of the dot products and lengths is far below kRelativeMargin * scale.
  h -= kRelativeMargin * scale;
  perp += kRelativeMargin * scale;
  if (h > rho) {
    const double angle = std::atan2(perp + rho, h - rho) + kConeAngleMargin;
    if (angle < kHalfPi && (!best.valid || angle < best.angle))
      best = {main.axis, angle, true, BackPatchVerdict::BackFacing};
  }
  return best;
}

}  // namespace

namespace {

// The products of Bernstein bases of the normal patch: B2_i(u) B3_k(u) = kDegreeU[i][k]
// B5_{i+k}(u) with kDegreeU[i][k] = C(2,i) C(3,k) / C(5,i+k), and B3_j(v) B2_l(v) = kDegreeV[j][l]
// B5_{j+l}(v); computed at compile time with the same operations the loops used to do.
struct DegreeProducts {
  double u[3][4], v[4][3];
};
constexpr DegreeProducts degreeProducts() {
  constexpr double C2[3] = {1, 2, 1}, C3[4] = {1, 3, 3, 1}, C5[6] = {1, 5, 10, 10, 5, 1};
  DegreeProducts w{};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 4; ++k) w.u[i][k] = C2[i] * C3[k] / C5[i + k];
  for (int j = 0; j < 4; ++j)
    for (int l = 0; l < 3; ++l) w.v[j][l] = C3[j] * C2[l] / C5[j + l];
  return w;
}
constexpr DegreeProducts kDegree = degreeProducts();

// The 12 control vectors of Bu, 3 (b[i+1,j] - b[i,j]) at 3 * j + i, and the 12 of Bv,
// 3 (b[k,l+1] - b[k,l]) at 4 * l + k.
void derivativeNets(std::span<const glm::dvec3> bezier, glm::dvec3 du[12], glm::dvec3 dv[12]) {
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i) du[3 * j + i] = 3.0 * (bezier[4 * j + i + 1] - bezier[4 * j + i]);
  for (int l = 0; l < 3; ++l)
    for (int k = 0; k < 4; ++k) dv[4 * l + k] = 3.0 * (bezier[4 * (l + 1) + k] - bezier[4 * l + k]);
}

// The normal patch from the derivative nets (derivativeNets).
// Bu = Σ 3 (b[i+1,j] - b[i,j]) B2_i(u) B3_j(v); Bv = Σ 3 (b[k,l+1] - b[k,l]) B3_k(u) B2_l(v).
std::array<glm::dvec3, 36> normalPatchOf(const glm::dvec3 du[12], const glm::dvec3 dv[12]) {
  std::array<glm::dvec3, 36> n;
  n.fill(glm::dvec3(0.0));
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i)
      for (int l = 0; l < 3; ++l)
        for (int k = 0; k < 4; ++k) {
          const double w = kDegree.u[i][k] * kDegree.v[j][l];
          n[6 * (j + l) + i + k] += w * glm::cross(du[3 * j + i], dv[4 * l + k]);
        }
  return n;
}

}  // namespace

std::array<glm::dvec3, 36> normalPatch(std::span<const glm::dvec3> bezier) {
  requireSize(bezier, 16, "bicubic Bézier");
  glm::dvec3 du[12], dv[12];
  derivativeNets(bezier, du, dv);
  return normalPatchOf(du, dv);
}

ConeOfNormals buildConeOfNormals(std::span<const glm::dvec3> bezier, ConeSearch search) {
  requireSize(bezier, 16, "bicubic Bézier");
  if (!allFinite(bezier)) return invalidCone(BackPatchVerdict::NonFinite);
  glm::dvec3 du[12], dv[12];
  derivativeNets(bezier, du, dv);
  const std::array<glm::dvec3, 36> n = normalPatchOf(du, dv);
  // Error bound of each coefficient: kRelativeMargin times the sum of |w| |du| |dv| of its
  // terms (the rounding error of the sum is below 100 ulps of that).
  double duLength[12], dvLength[12];
  for (int e = 0; e < 12; ++e) duLength[e] = glm::length(du[e]), dvLength[e] = glm::length(dv[e]);
  std::array<double, 36> err{};
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i)
      for (int l = 0; l < 3; ++l)
        for (int k = 0; k < 4; ++k)
          err[6 * (j + l) + i + k] +=
              kDegree.u[i][k] * kDegree.v[j][l] * duLength[3 * j + i] * dvLength[4 * l + k];
  for (double& e : err) e *= kRelativeMargin;
  const DirectionCone cone = boundDirections(n, err, search);
  if (!cone.valid) return invalidCone(cone.reason);
  ConeOfNormals result = withApex(cone.axis, cone.angle, bezier);
  // N(u,v) is a convex combination of the coefficients: N . a >= min (n_k . a - err_k).
  double minNormal = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < n.size(); ++k)
    minNormal = std::min(minNormal, glm::dot(n[k], cone.axis) - 2.0 * err[k]);
  result.minNormal = std::max(0.0, minNormal);
  return result;
}

ConeOfNormals buildConeFromTangentCones(std::span<const glm::dvec3> bezier, ConeSearch search) {
  requireSize(bezier, 16, "bicubic Bézier");
  if (!allFinite(bezier)) return invalidCone(BackPatchVerdict::NonFinite);
  std::array<glm::dvec3, 12> du, dv;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i) {
      du[3 * j + i] = bezier[4 * j + i + 1] - bezier[4 * j + i];    // tangent patch (§2, SM88)
      dv[3 * j + i] = bezier[4 * (i + 1) + j] - bezier[4 * i + j];  // bitangent patch
    }
  // Differences of doubles are exact to an ulp: their directions are covered by the angle
  // margin, so no per-vector error is needed.
  const std::array<double, 12> zero{};
  const DirectionCone cu = boundDirections(du, zero, search),
                      cv = boundDirections(dv, zero, search);
  ConeOfNormals result = combineTangentCones(cu, cv, bezier);
  if (result.valid) result.minNormal = tangentConesMinNormal(du, dv, cu, cv);
  return result;
}

ConeOfNormals buildGregoryConeFromTangentCones(std::span<const glm::dvec3> gregory,
                                               ConeSearch search) {
  requireSize(gregory, 20, "Gregory");
  if (!allFinite(gregory)) return invalidCone(BackPatchVerdict::NonFinite);
  // Candidates of each 4x4 Bézier-net position: its boundary point, or both interior points.
  auto candidates = [&](int i, int j, glm::dvec3 out[2]) {
    const int k = 4 * j + i;
    if (kGregoryBoundary[k] >= 0) {
      out[0] = gregory[kGregoryBoundary[k]];
      return 1;
    }
    for (const GregoryInterior& g : kGregoryInterior)
      if (g.i == i && g.j == j) {
        out[0] = gregory[g.a];
        out[1] = gregory[g.b];
        return 2;
      }
    return 0;
  };
  std::vector<glm::dvec3> du, dv;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 3; ++i) {
      glm::dvec3 hi[2], lo[2];
      // u direction: net(i+1, j) - net(i, j), each a convex blend of its candidates.
      int nh = candidates(i + 1, j, hi), nl = candidates(i, j, lo);
      for (int x = 0; x < nh; ++x)
        for (int y = 0; y < nl; ++y) du.push_back(hi[x] - lo[y]);
      // v direction: net(j, i+1) - net(j, i) (i walks v here).
      nh = candidates(j, i + 1, hi);
      nl = candidates(j, i, lo);
      for (int x = 0; x < nh; ++x)
        for (int y = 0; y < nl; ++y) dv.push_back(hi[x] - lo[y]);
    }
  // Derivatives of the rational blends: d/du of (a A + b B)/(a + b) is
  // (a_u b - a b_u)/(a + b)² (A - B); a_u b - a b_u is linear in (u, v), so its sign on
  // the unit square is that of its four corner values.
  std::vector<glm::dvec3> ru, rv;
  auto addBlendDerivative = [&](const GregoryInterior& g, bool alongU,
                                std::vector<glm::dvec3>& out) {
    const glm::dvec3 diff = gregory[g.a] - gregory[g.b];
    bool positive = false, negative = false;
    for (int corner = 0; corner < 4; ++corner) {
      const double s = corner & 1, t = corner >> 1;
      const double a = g.a0 + g.as * s + g.at * t, b = g.b0 + g.bs * s + g.bt * t;
      const double value = alongU ? g.as * b - a * g.bs : g.at * b - a * g.bt;
      positive |= value > 0.0;
      negative |= value < 0.0;
    }
    if (positive) out.push_back(diff);
    if (negative) out.push_back(-diff);
  };
  for (const GregoryInterior& g : kGregoryInterior) {
    addBlendDerivative(g, true, ru);
    addBlendDerivative(g, false, rv);
  }
  return combineTangentCones(gregoryTangentCone(du, ru, search), gregoryTangentCone(dv, rv, search),
                             gregory);
}

BackPatchResult testConeOfNormals(const ConeOfNormals& cone, const glm::dvec3& eye) {
  if (!cone.valid) return {false, cone.reason};
  if (!std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z))
    return {false, BackPatchVerdict::NonFinite};
  const glm::dvec3 d = eye - cone.apex;
  const double lhs = glm::dot(cone.axis, d) + cone.sinAngle * glm::length(d);
  const double margin = kRelativeMargin * (glm::length(eye) + glm::length(cone.apex));
  if (lhs < -margin) return {true, BackPatchVerdict::BackFacing};
  return {false, BackPatchVerdict::EyeOutsideBackRegion};
}

}  // namespace osd_cull::bound
