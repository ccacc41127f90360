#include "osd_cull/bound/patch_clusters.h"

#include "osd_cull/bound/clip_space.h"
#include "osd_cull/error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <queue>
#include <set>
#include <string>
#include <tuple>

namespace osd_cull::bound {

namespace {

// Γ is kept below this: a wider cone decides too rarely to pay, and cos Γ bounds the margin
// of the cull region (below).
constexpr double kMaxClusterAngle = 85.0 * 3.14159265358979323846 / 180.0;
// The cull region lies this far inside every member's, relative to the magnitudes, so that
// the members' fp32 kernel tests (margin kCullRelativeMargin = 1e-5, error < 1e-6) cull
// every member of a cluster the cluster test culls.
constexpr double kRegionMargin = 1e-4;

struct Cone {
  glm::dvec3 axis{0.0, 0.0, 1.0};
  double angle = 0.0;
  bool valid = false;
};

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// The smallest cone holding both (Γ ≥ angle(A, a_i) + γ_i for both): the containing one,
// or the cone whose boundary touches both, with the axis rotated from a toward b.
Cone mergeCones(const Cone& a, const Cone& b) {
  if (!a.valid || !b.valid) return {};
  const double theta = angleBetween(a.axis, b.axis);
  if (theta + b.angle <= a.angle) return a;
  if (theta + a.angle <= b.angle) return b;
  Cone c;
  c.angle = 0.5 * (theta + a.angle + b.angle);
  if (!(c.angle < kMaxClusterAngle)) return {};
  const glm::dvec3 ortho = b.axis - glm::dot(a.axis, b.axis) * a.axis;
  const double len = glm::length(ortho);
  if (!(len > 1e-12)) return {};
  const double phi = c.angle - a.angle;
  c.axis = glm::normalize(std::cos(phi) * a.axis + std::sin(phi) * (ortho / len));
  c.valid = true;
  return c;
}

struct Group {
  glm::dvec3 lo{0.0}, hi{0.0};
  Cone cone;
  std::vector<uint32_t> patches;
  uint32_t version = 0;
  bool alive = true;
};

// T = t + n w + (1 - P) n r with r = 1 (ClusterCostModel): P, the chance that the test
// decides, is the share of view directions in the cone's front or back region, 1 - sin Γ
// (each region is a cone of half-angle 90° - Γ: (1 - sin Γ) / 2 of the sphere), 0 for an
// invalid cone; frustum-only clusters (no cones) decide by their box, taken as P = 1.
double cost(const Group& g, const ClusterCostModel& model, bool cones) {
  const double n = double(g.patches.size());
  const double p = !cones ? 1.0 : g.cone.valid ? 1.0 - std::sin(g.cone.angle) : 0.0;
  return model.clusterTest + n * model.memberWrite + (1.0 - p) * n;
}

Group merged(const Group& a, const Group& b) {
  Group m;
  m.lo = glm::min(a.lo, b.lo);
  m.hi = glm::max(a.hi, b.hi);
  m.cone = mergeCones(a.cone, b.cone);
  m.patches = a.patches;
  m.patches.insert(m.patches.end(), b.patches.begin(), b.patches.end());
  return m;
}

// The apex of the cull region: L = c - t A with the least t (bisection) at which L lies in
// every member's cull region with the margin kRegionMargin (|L| + |l_i|). Each member's
// condition g_i(t) = a_i.(L - l_i) + s_i |L - l_i| + margin (|L| + |l_i|) is
// convex in t with slope tending to s_i - cos angle(A, a_i) + 2 margin < 0 (Γ < 85° and
// the cull angle's slack), so the points where all hold form one interval [t*, ∞).
std::optional<glm::dvec3> cullApex(const glm::dvec3& centre, const glm::dvec3& axis,
                                   std::span<const ConeOfNormals> members, double scale) {
  auto worst = [&](double t) {
    const glm::dvec3 l = centre - t * axis;
    double g = -1.0;
    for (const ConeOfNormals& c : members) {
      const glm::dvec3 d = l - c.apex;
      const double m = kRegionMargin * (glm::length(l) + glm::length(c.apex));
      g = std::max(g, glm::dot(c.axis, d) + c.sinAngle * glm::length(d) + m);
    }
    return g;
  };
  if (worst(0.0) <= 0.0) return centre;
  double hi = std::max(scale, 1e-30);
  for (int i = 0; i < 200 && worst(hi) > 0.0; ++i) hi *= 2.0;
  if (!(worst(hi) <= 0.0)) return std::nullopt;
  double lo = 0.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (worst(mid) <= 0.0 ? hi : lo) = mid;
  }
  return centre - hi * axis;
}

double roundUpSin(double angle) { return std::min(1.0, std::sin(angle) * (1.0 + 1e-12) + 1e-15); }

// The final cluster from a group: the box, the cone recomputed exactly from the members
// (Γ = max angle(A, a_i) + γ_i), and the cull region: angle Γ + δ with δ cos(Γ + δ) >=
// kRegionMargin (so every direction of the region lies inside every member's by that
// margin) and its apex (cullApex).
PatchCluster finish(const Group& g, std::span<const ConeOfNormals> cones, const PatchSet& patches,
                    std::vector<uint32_t>& members) {
  PatchCluster c;
  c.boxMin = g.lo;
  c.boxMax = g.hi;
  c.first = uint32_t(members.size());
  std::vector<uint32_t> sorted = g.patches;
  std::sort(sorted.begin(), sorted.end());
  for (uint32_t p : sorted) (p < patches.bezierCount ? c.bezierCount : c.gregoryCount)++;
  members.insert(members.end(), sorted.begin(), sorted.end());
  if (cones.empty() || !g.cone.valid) return c;
  std::vector<ConeOfNormals> own;
  double gamma = 0.0;
  for (uint32_t p : sorted) {
    if (!cones[p].valid) return c;
    own.push_back(cones[p]);
    gamma = std::max(gamma, angleBetween(g.cone.axis, cones[p].axis) + cones[p].angle);
  }
  gamma += kConeAngleMargin;
  if (!(gamma < kMaxClusterAngle)) return c;
  c.axis = g.cone.axis;
  c.angle = gamma;
  c.sinAngle = roundUpSin(gamma);
  const double delta = 2.0 * kRegionMargin / std::cos(gamma) + 1e-9;
  const double cullAngle = gamma + delta;
  if (!(cullAngle < kMaxClusterAngle + 0.01)) return c;
  const glm::dvec3 centre = 0.5 * (g.lo + g.hi);
  const std::optional<glm::dvec3> apex =
      cullApex(centre, c.axis, own, glm::length(g.hi - g.lo) + 1e-9 * glm::length(centre));
  if (!apex) return c;
  c.apex = *apex;
  c.cullSinAngle = roundUpSin(cullAngle);
  c.coneValid = true;
  return c;
}

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

PatchClusters buildPatchClusters(const PatchSet& patches, std::span<const ConeOfNormals> cones,
                                 const ClusterCostModel& model) {
  const uint32_t n = patches.patchCount();
  if (!cones.empty() && cones.size() != n)
    throw Error("buildPatchClusters: " + std::to_string(cones.size()) + " cones for " +
                std::to_string(n) + " patches of " + patches.source);
  if (model.maxPatches == 0) throw Error("buildPatchClusters: maxPatches must be at least 1");
  const bool withCones = !cones.empty();
  // One group per patch to start: grouping a base face's patches (PatchParam face id) up
  // front would merge without asking the model, and a face's patches can span a wide cone.
  std::vector<Group> groups(n);
  std::vector<uint32_t> groupOf(n);
  for (uint32_t p = 0; p < n; ++p) {
    const std::span<const glm::dvec3> points = patches.controlPoints(p);
    Group& g = groups[p];
    g.lo = g.hi = points[0];
    for (const glm::dvec3& q : points) {
      g.lo = glm::min(g.lo, q);
      g.hi = glm::max(g.hi, q);
    }
    if (withCones && cones[p].valid) g.cone = {cones[p].axis, cones[p].angle, true};
    g.patches = {p};
    groupOf[p] = p;
  }
  // Neighbours: groups whose patches share a corner point (the limit surface's corners,
  // shared by patches of neighbouring base faces up to the rounding of each patch's
  // conversion to Bézier form): corners within 1e-7 of the set's extent, found through a
  // grid of that cell size and the 27 cells around each corner.
  glm::dvec3 lo(0.0), hi(0.0);
  if (!patches.points.empty()) lo = hi = patches.points.front();
  for (const glm::dvec3& q : patches.points)
    if (finite(q)) lo = glm::min(lo, q), hi = glm::max(hi, q);
  const double cell = std::max(1e-7 * glm::length(hi - lo), 1e-300);
  using Cell = std::tuple<int64_t, int64_t, int64_t>;
  auto cellOf = [&](const glm::dvec3& q) {
    const glm::dvec3 g = glm::floor((q - lo) / cell);
    return Cell{int64_t(g.x), int64_t(g.y), int64_t(g.z)};
  };
  std::map<Cell, std::vector<uint32_t>> byCell;
  std::vector<std::pair<glm::dvec3, uint32_t>> corners;
  for (uint32_t p = 0; p < n; ++p) {
    const std::span<const glm::dvec3> points = patches.controlPoints(p);
    static constexpr uint32_t kBezierCorners[4] = {0, 3, 12, 15};
    static constexpr uint32_t kGregoryCorners[4] = {0, 5, 10, 15};
    for (uint32_t k : p < patches.bezierCount ? kBezierCorners : kGregoryCorners) {
      if (!finite(points[k])) continue;
      byCell[cellOf(points[k])].push_back(groupOf[p]);
      corners.emplace_back(points[k], groupOf[p]);
    }
  }
  std::vector<std::set<uint32_t>> neighbours(groups.size());
  for (const auto& [q, a] : corners) {
    const auto [x, y, z] = cellOf(q);
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = byCell.find({x + dx, y + dy, z + dz});
          if (it == byCell.end()) continue;
          for (uint32_t b : it->second)
            if (b != a) neighbours[a].insert(b);
        }
  }
  // Greedy merging, best gain first: T(A) + T(B) - T(A ∪ B) > 0 (the lecture's criterion).
  using Candidate =
      std::tuple<double, uint32_t, uint32_t, uint32_t, uint32_t>;  // gain, a, b, versions
  std::priority_queue<Candidate> queue;
  auto consider = [&](uint32_t a, uint32_t b) {
    const Group& ga = groups[a];
    const Group& gb = groups[b];
    if (ga.patches.size() + gb.patches.size() > model.maxPatches) return;
    const double gain = cost(ga, model, withCones) + cost(gb, model, withCones) -
                        cost(merged(ga, gb), model, withCones);
    if (gain > 0.0) queue.emplace(gain, a, b, ga.version, gb.version);
  };
  for (uint32_t a = 0; a < groups.size(); ++a)
    for (uint32_t b : neighbours[a])
      if (a < b) consider(a, b);
  while (!queue.empty()) {
    const auto [gain, a, b, va, vb] = queue.top();
    queue.pop();
    if (!groups[a].alive || !groups[b].alive || groups[a].version != va || groups[b].version != vb)
      continue;
    groups[a] = merged(groups[a], groups[b]);
    groups[a].version = va + 1;
    groups[b].alive = false;
    groups[b].patches.clear();
    for (uint32_t c : neighbours[b])
      if (c != a) {
        neighbours[a].insert(c);
        neighbours[c].erase(b);
        neighbours[c].insert(a);
      }
    neighbours[a].erase(b);
    neighbours[b].clear();
    for (uint32_t c : neighbours[a])
      if (groups[c].alive) consider(a, c);
  }
  PatchClusters out;
  out.members.reserve(n);
  for (const Group& g : groups)
    if (g.alive && !g.patches.empty()) {
      out.clusters.push_back(finish(g, cones, patches, out.members));
      out.modelCost += cost(g, model, withCones);
    }
  out.perPatchCost = double(n);
  return out;
}

ClusterResult testCluster(const PatchCluster& cluster, const CullView& view,
                          const ClusterTests& tests) {
  const glm::dvec3 c = 0.5 * (cluster.boxMin + cluster.boxMax);
  const glm::dvec3 e = 0.5 * (cluster.boxMax - cluster.boxMin);
  if (!finite(c) || !finite(e)) return {};
  bool inside = true;
  if (tests.frustum) {
    // Clip-space planes q = r_a +- r_b of the rows of viewProj (bound::FrustumPlane order);
    // over the box q.(p, 1) ranges over q.(c, 1) -+ |q.xyz|.e, and |r_a|.(|c| + e, 1) +
    // |r_b|.(|c| + e, 1) bounds every product (as the kernel's box test, frustum.glsl).
    const glm::dmat4& m = view.viewProj;
    auto row = [&](int r) { return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
    const glm::dvec4 rx = row(0), ry = row(1), rz = row(2), rw = row(3);
    const glm::dvec4 planes[6] = {rw + rx, rw - rx, rw + ry, rw - ry, rz, rw - rz};
    const glm::dvec4 ca(glm::abs(c) + e, 1.0);
    const double mx = glm::dot(glm::abs(rx), ca), my = glm::dot(glm::abs(ry), ca),
                 mz = glm::dot(glm::abs(rz), ca), mw = glm::dot(glm::abs(rw), ca);
    const double mags[6] = {mw + mx, mw + mx, mw + my, mw + my, mz, mw + mz};
    for (uint32_t p = 0; p < 6; ++p) {
      const glm::dvec3 q(planes[p]);
      const double mid = glm::dot(q, c) + planes[p].w;
      const double spread = glm::dot(glm::abs(q), e);
      const double margin = kRelativeMargin * mags[p];
      if (!std::isfinite(mid) || !std::isfinite(spread) || !std::isfinite(margin)) return {};
      if (mid + spread < -margin) return {ClusterVerdict::CulledFrustum, p};
      if (!(mid - spread > margin)) inside = false;
    }
  }
  bool front = !tests.backPatch;
  if (tests.backPatch && cluster.coneValid && view.eye && finite(*view.eye)) {
    const glm::dvec3 eye = *view.eye;
    if (tests.backCull) {
      const glm::dvec3 d = eye - cluster.apex;
      const double lhs = glm::dot(cluster.axis, d) + cluster.cullSinAngle * glm::length(d);
      if (lhs < -kRelativeMargin * (glm::length(eye) + glm::length(cluster.apex)))
        return {ClusterVerdict::CulledBackFacing, 6};
    }
    // Front-facing from every point p of the box: A.(E - p) > sin Γ |E - p| for all p. The
    // left side minus the right is concave in p, so its least value over the box is at a
    // corner: the eight corners decide.
    front = true;
    for (int k = 0; k < 8 && front; ++k) {
      const glm::dvec3 p((k & 1) ? cluster.boxMax.x : cluster.boxMin.x,
                         (k & 2) ? cluster.boxMax.y : cluster.boxMin.y,
                         (k & 4) ? cluster.boxMax.z : cluster.boxMin.z);
      const glm::dvec3 d = eye - p;
      const double f = glm::dot(cluster.axis, d) - cluster.sinAngle * glm::length(d);
      front = f > kRelativeMargin * (glm::length(eye) + glm::length(p));
    }
  }
  if (tests.accept && inside && front) return {ClusterVerdict::Accepted, 6};
  return {};
}

}  // namespace osd_cull::bound
