#pragma once
// Shared fixtures of the tests/test_bound_*.cpp suites: random and procedural Bézier
// patches (random nets, bumps, planes, saddles, collapsed edges, a Bézier sphere with
// collapsed poles, a B-spline torus), Gregory versions of them, and random views of the
// kinds the cull tests must survive (around, inside the bounding box, close to the surface,
// crossing the near plane, looking away), with y flips and mirrored views.

#include "adapters/load_mesh.h"
#include "osd_cull/bound/patch_eval.h"
#include "osd_cull/patch/bspline_bezier.h"
#include "osd_cull/patch/cage_mesh.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/procedural.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace osd_cull::bound::test {

using Bezier = std::array<glm::dvec3, 16>;
using Gregory = std::array<glm::dvec3, 20>;
inline constexpr double kPi = std::numbers::pi;

struct Rng {
  std::mt19937_64 engine;
  explicit Rng(uint64_t seed) : engine(seed) {}
  double uniform(double lo = 0.0, double hi = 1.0) {
    return std::uniform_real_distribution<double>(lo, hi)(engine);
  }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(engine); }
  glm::dvec3 inBox(double r) { return {uniform(-r, r), uniform(-r, r), uniform(-r, r)}; }
  glm::dvec3 direction() {
    const double z = uniform(-1.0, 1.0), phi = uniform(0.0, 2.0 * kPi);
    const double s = std::sqrt(1.0 - z * z);
    return {s * std::cos(phi), s * std::sin(phi), z};
  }
};

// A random rigid motion with uniform scale, applied to a patch.
inline Bezier transformed(const Bezier& b, Rng& rng, double scale = 1.0) {
  const glm::dvec3 axis = rng.direction();
  const glm::dmat4 rot = glm::rotate(glm::dmat4(1.0), rng.uniform(0.0, 2.0 * kPi), axis);
  const glm::dvec3 shift = rng.inBox(2.0);
  Bezier out;
  for (size_t k = 0; k < 16; ++k) out[k] = scale * glm::dvec3(rot * glm::dvec4(b[k], 1.0)) + shift;
  return out;
}

enum class PatchKind { RandomNet, SmoothBump, Planar, Saddle, CollapsedEdge, Count };
inline const char* name(PatchKind k) {
  switch (k) {
    case PatchKind::RandomNet:
      return "random-net";
    case PatchKind::SmoothBump:
      return "smooth-bump";
    case PatchKind::Planar:
      return "planar";
    case PatchKind::Saddle:
      return "saddle";
    case PatchKind::CollapsedEdge:
      return "collapsed-edge";
    default:
      return "?";
  }
}

// A unit-sized patch of the given kind, randomly placed around the origin.
inline Bezier randomBezier(Rng& rng, PatchKind kind) {
  Bezier b;
  const double h = rng.uniform(-0.6, 0.6);
  const double c[4] = {0.0, 0.0, 1.0 / 3.0, 1.0};  // Bézier coefficients of t² (degree 3)
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const glm::dvec3 grid(i / 3.0 - 0.5, j / 3.0 - 0.5, 0.0);
      glm::dvec3 p = grid;
      switch (kind) {
        case PatchKind::RandomNet:
          p += rng.inBox(0.35);
          break;
        case PatchKind::SmoothBump:
          p.z =
              h * ((i == 1 || i == 2) && (j == 1 || j == 2) ? 1.0 : 0.0) + rng.uniform(-0.05, 0.05);
          break;
        case PatchKind::Planar:
          p += glm::dvec3(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), 0.0);
          break;
        case PatchKind::Saddle:
          p.z = h * (c[i] - c[j]);
          break;
        case PatchKind::CollapsedEdge:
          // Teapot-lid style: row 0 collapses to one point, a dome rises toward it.
          p.z = h * (j == 0 ? 1.0 : (j == 1 ? 0.8 : 0.3 * (i == 1 || i == 2)));
          if (j == 0) p.x = p.y = -0.5;
          break;
        default:
          break;
      }
      b[4 * j + i] = p;
    }
  return transformed(b, rng);
}

// Circle arc from angle a0 to a1 as a cubic Bézier (2D points), k = 4/3 tan(Δ/4).
inline std::array<glm::dvec2, 4> arc(double a0, double a1) {
  const double k = 4.0 / 3.0 * std::tan((a1 - a0) / 4.0);
  const glm::dvec2 p0(std::cos(a0), std::sin(a0)), p3(std::cos(a1), std::sin(a1));
  return {p0, p0 + k * glm::dvec2(-p0.y, p0.x), p3 - k * glm::dvec2(-p3.y, p3.x), p3};
}

// A closed, outward-oriented Bézier sphere: the tensor product of a longitude arc c(u) and
// a meridian arc m(v) = (rho, z), B = (c.x rho, c.y rho, z), u east, v from south to north.
// The pole rows collapse to one point each (teapot-lid style, exact equal points).
inline std::vector<Bezier> bezierSphere(int lon, int lat, double radius = 1.0) {
  std::vector<Bezier> out;
  for (int b = 0; b < lat; ++b) {
    const double l0 = -kPi / 2 + kPi * b / lat, l1 = -kPi / 2 + kPi * (b + 1) / lat;
    std::array<glm::dvec2, 4> m = arc(l0, l1);
    if (b == 0) m[0] = {0.0, -1.0};  // exact poles
    if (b == lat - 1) m[3] = {0.0, 1.0};
    for (int a = 0; a < lon; ++a) {
      const std::array<glm::dvec2, 4> c = arc(2 * kPi * a / lon, 2 * kPi * (a + 1) / lon);
      Bezier p;
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
          p[4 * j + i] = radius * glm::dvec3(c[i].x * m[j].x, c[i].y * m[j].x, m[j].y);
      out.push_back(p);
    }
  }
  return out;
}

// A closed torus-like surface: a periodic uniform bicubic B-spline whose control points
// lie on a torus (u around the z axis, v around the tube: outward normals), each patch
// converted to Bézier form.
inline std::vector<Bezier> bsplineTorus(int n, int m, double major = 1.0, double minor = 0.4) {
  auto cp = [&](int a, int b) {
    const double phi = 2 * kPi * ((a % n + n) % n) / n, psi = 2 * kPi * ((b % m + m) % m) / m;
    return glm::dvec3((major + minor * std::cos(psi)) * std::cos(phi),
                      (major + minor * std::cos(psi)) * std::sin(phi), minor * std::sin(psi));
  };
  std::vector<Bezier> out;
  for (int b = 0; b < m; ++b)
    for (int a = 0; a < n; ++a) {
      std::array<glm::dvec3, 16> cv;
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) cv[4 * y + x] = cp(a + x - 1, b + y - 1);
      out.push_back(bsplineToBezier(cv, 0u));
    }
  return out;
}

// The Gregory patch equal to a Bézier patch, with its Fp/Fm pairs pulled apart by up to
// `split` (boundary unchanged, so a closed set of patches stays closed).
inline Gregory gregoryFromBezier(const Bezier& b, Rng& rng, double split) {
  Gregory g{};
  for (int k = 0; k < 16; ++k)
    if (kGregoryBoundary[k] >= 0) g[kGregoryBoundary[k]] = b[k];
  for (const GregoryInterior& in : kGregoryInterior) {
    const glm::dvec3 p = b[4 * in.j + in.i];
    g[in.a] = p + rng.inBox(split);
    g[in.b] = p + rng.inBox(split);
  }
  return g;
}

// A view: the view-projection matrix and the eye it was built from.
struct View {
  glm::dmat4 viewProj{1.0};
  glm::dvec3 eye{0.0};
};

enum class ViewKind { Around, InsideBox, NearSurface, CrossingNear, LookingAway, Count };
inline const char* name(ViewKind k) {
  switch (k) {
    case ViewKind::Around:
      return "around";
    case ViewKind::InsideBox:
      return "inside-box";
    case ViewKind::NearSurface:
      return "near-surface";
    case ViewKind::CrossingNear:
      return "crossing-near";
    case ViewKind::LookingAway:
      return "looking-away";
    default:
      return "?";
  }
}

inline View makeView(Rng& rng, const glm::dvec3& eye, const glm::dvec3& target, double nearPlane,
                     double farPlane) {
  // Random numbers are drawn unconditionally, so that scaled copies of a scene (same seed)
  // get the same views even where a rounding-level difference picks another branch.
  const glm::dvec3 fallback = rng.direction(), up0 = rng.direction(), up1 = rng.direction();
  glm::dvec3 forward = target - eye;
  if (!(glm::length(forward) > 0.0)) forward = fallback;
  glm::dvec3 up = up0;
  if (glm::length(glm::cross(up, forward)) < 1e-3 * glm::length(forward)) up = up1;
  const glm::dmat4 view = glm::lookAt(eye, eye + forward, up);
  const double fovy = rng.uniform(0.35, 1.9), aspect = rng.uniform(0.5, 2.0);
  glm::dmat4 proj = glm::perspective(fovy, aspect, nearPlane, farPlane);
  if (rng.uniform() < 0.3) {  // off-centre frustum
    const double t = nearPlane * std::tan(fovy / 2), r = t * aspect;
    proj = glm::frustum(-r * rng.uniform(0.2, 1.5), r * rng.uniform(0.2, 1.5),
                        -t * rng.uniform(0.2, 1.5), t * rng.uniform(0.2, 1.5), nearPlane, farPlane);
  }
  if (rng.uniform() < 0.5) proj[1][1] = -proj[1][1];  // Vulkan y flip: det < 0
  glm::dmat4 mirror(1.0);
  if (rng.uniform() < 0.25) mirror[0][0] = -1.0;  // mirrored image: det < 0
  return {mirror * proj * view, eye};
}

// A random view of an object with centre `centre` and radius `radius`; NearSurface puts the
// eye within 1e-6..1e-1 radius of the surface point `onSurface` (either side).
inline View randomView(Rng& rng, ViewKind kind, const glm::dvec3& centre, double radius,
                       const glm::dvec3& onSurface, const glm::dvec3& surfaceNormal) {
  switch (kind) {
    case ViewKind::Around: {
      const double dist = radius * rng.uniform(1.2, 8.0);
      const glm::dvec3 eye = centre + dist * rng.direction();
      return makeView(rng, eye, centre + rng.inBox(0.7 * radius), dist * rng.uniform(0.01, 0.5),
                      dist * rng.uniform(0.8, 3.0));
    }
    case ViewKind::InsideBox: {
      const glm::dvec3 eye = centre + rng.inBox(radius);
      return makeView(rng, eye, eye + rng.direction(), radius * rng.uniform(1e-3, 0.1),
                      radius * rng.uniform(1.0, 10.0));
    }
    case ViewKind::NearSurface: {
      const double len = glm::length(surfaceNormal);
      const glm::dvec3 fallback = rng.direction();
      const glm::dvec3 n = len > 0.0 ? surfaceNormal / len : fallback;
      const double side = rng.uniform() < 0.5 ? -1.0 : 1.0;
      const glm::dvec3 eye =
          onSurface + side * radius * std::pow(10.0, rng.uniform(-6.0, -1.0)) * n;
      return makeView(rng, eye, eye + rng.direction(), radius * 1e-7, radius * 10.0);
    }
    case ViewKind::CrossingNear: {
      const double dist = radius * rng.uniform(0.3, 3.0);
      const glm::dvec3 eye = centre + dist * rng.direction();
      return makeView(rng, eye, centre, dist * rng.uniform(0.5, 1.5), dist * 4.0 + radius);
    }
    case ViewKind::LookingAway:
    default: {
      const glm::dvec3 eye = centre + radius * rng.uniform(0.5, 4.0) * rng.direction();
      return makeView(rng, eye, eye + (eye - centre) + rng.inBox(0.5 * radius),
                      radius * rng.uniform(1e-3, 0.2), radius * 20.0);
    }
  }
}

// Centre and radius of a set of points.
template <class Points>
inline void boundingSphere(const Points& pts, glm::dvec3* centre, double* radius) {
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const glm::dvec3& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
  *centre = 0.5 * (lo + hi);
  *radius = 0.5 * glm::length(hi - lo);
}

// The patches of a cage as osd_cull::extractPatches gives them (adaptive refinement to
// `level`, Gregory-basis end caps), split into Bézier and Gregory point arrays.
struct CagePatches {
  PatchExtraction extraction;
  std::vector<Bezier> bezier;
  std::vector<Gregory> gregory;
};

inline CagePatches cagePatches(const CageMesh& cage, int level) {
  PatchOptions options;
  options.isolationLevel = level;
  CagePatches out{extractPatches(cage, options), {}, {}};
  const PatchSet& set = out.extraction.patches;
  for (uint32_t p = 0; p < set.patchCount(); ++p) {
    const std::span<const glm::dvec3> cps = set.controlPoints(p);
    if (set.type(p) == PatchType::Bezier)
      std::copy(cps.begin(), cps.end(), out.bezier.emplace_back().begin());
    else
      std::copy(cps.begin(), cps.end(), out.gregory.emplace_back().begin());
  }
  return out;
}

// The Bézier patches of a BPT file (adapters::loadBezierPatches).
inline std::vector<Bezier> bptPatches(const std::filesystem::path& path) {
  const PatchSet set = adapters::loadBezierPatches(path);
  std::vector<Bezier> out(set.bezierCount);
  for (uint32_t p = 0; p < set.bezierCount; ++p)
    std::copy_n(set.controlPoints(p).begin(), kBezierPoints, out[p].begin());
  return out;
}

}  // namespace osd_cull::bound::test
