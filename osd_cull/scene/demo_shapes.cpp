#include "osd_cull/scene/demo_shapes.h"

#include "osd_cull/error.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <cmath>

namespace osd_cull::scene {

namespace {

using Patch16 = std::array<glm::dvec3, 16>;

OpenSubdiv::Far::PatchParam makeParam(uint32_t faceId, unsigned short u, unsigned short v,
                                      unsigned short depth, unsigned short transition) {
  OpenSubdiv::Far::PatchParam p;
  p.Set(static_cast<OpenSubdiv::Far::Index>(faceId), static_cast<short>(u), static_cast<short>(v),
        depth, false, 0, transition, true);
  return p;
}

// Splits a Bézier patch at u = 1/2 and v = 1/2: children (0,0), (1,0), (0,1), (1,1).
std::array<Patch16, 4> splitQuarters(const Patch16& b) {
  auto splitCurve = [](const std::array<glm::dvec3, 4>& c, std::array<glm::dvec3, 4>& left,
                       std::array<glm::dvec3, 4>& right) {
    const glm::dvec3 b01 = 0.5 * (c[0] + c[1]), b12 = 0.5 * (c[1] + c[2]),
                     b23 = 0.5 * (c[2] + c[3]);
    const glm::dvec3 b012 = 0.5 * (b01 + b12), b123 = 0.5 * (b12 + b23);
    const glm::dvec3 m = 0.5 * (b012 + b123);
    left = {c[0], b01, b012, m};
    right = {m, b123, b23, c[3]};
  };
  // Split rows in u.
  Patch16 lu{}, ru{};
  for (int j = 0; j < 4; ++j) {
    std::array<glm::dvec3, 4> row{b[4 * j], b[4 * j + 1], b[4 * j + 2], b[4 * j + 3]}, l, r;
    splitCurve(row, l, r);
    for (int i = 0; i < 4; ++i) {
      lu[4 * j + i] = l[i];
      ru[4 * j + i] = r[i];
    }
  }
  std::array<Patch16, 4> out{};
  auto splitV = [&](const Patch16& p, Patch16& lo, Patch16& hi) {
    for (int i = 0; i < 4; ++i) {
      std::array<glm::dvec3, 4> col{p[i], p[4 + i], p[8 + i], p[12 + i]}, l, r;
      splitCurve(col, l, r);
      for (int j = 0; j < 4; ++j) {
        lo[4 * j + i] = l[j];
        hi[4 * j + i] = r[j];
      }
    }
  };
  splitV(lu, out[0], out[2]);
  splitV(ru, out[1], out[3]);
  return out;
}

}  // namespace

std::array<glm::dvec3, 16> flatBezierPatch(const glm::dvec3& origin, const glm::dvec3& du,
                                           const glm::dvec3& dv) {
  Patch16 p{};
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) p[4 * j + i] = origin + du * (i / 3.0) + dv * (j / 3.0);
  return p;
}

std::array<glm::dvec3, 20> gregoryFromBezier(std::span<const glm::dvec3, 16> b) {
  auto at = [&](int i, int j) { return b[4 * j + i]; };
  // Corner c: P, Ep (towards the next corner), Em (towards the previous), Fp, Fm
  // (see Osd_EvalBasisGregory's boundary and interior tables).
  return {at(0, 0), at(1, 0), at(0, 1), at(1, 1), at(1, 1), at(3, 0), at(3, 1),
          at(2, 0), at(2, 1), at(2, 1), at(3, 3), at(2, 3), at(3, 2), at(2, 2),
          at(2, 2), at(0, 3), at(0, 2), at(1, 3), at(1, 2), at(1, 2)};
}

PatchSet bezierPatchSet(std::span<const std::array<glm::dvec3, 16>> patches, std::string source) {
  PatchSet set;
  set.source = std::move(source);
  set.bezierCount = static_cast<uint32_t>(patches.size());
  for (uint32_t i = 0; i < patches.size(); ++i) {
    set.points.insert(set.points.end(), patches[i].begin(), patches[i].end());
    set.params.push_back(makeParam(i, 0, 0, 0, 0));
    set.origins.push_back(PatchOrigin::Input);
  }
  return set;
}

PatchSet convertToGregory(const PatchSet& set, const std::function<bool(uint32_t)>& toGregory) {
  PatchSet out;
  out.source = set.source;
  PatchSet gregory;
  for (uint32_t p = 0; p < set.bezierCount; ++p) {
    const auto cp = set.controlPoints(p);
    if (toGregory(p)) {
      const auto g = gregoryFromBezier(std::span<const glm::dvec3, 16>(cp.data(), 16));
      gregory.points.insert(gregory.points.end(), g.begin(), g.end());
      gregory.params.push_back(set.params[p]);
      gregory.origins.push_back(PatchOrigin::Gregory);
      ++gregory.gregoryCount;
    } else {
      out.points.insert(out.points.end(), cp.begin(), cp.end());
      out.params.push_back(set.params[p]);
      out.origins.push_back(set.origins[p]);
      ++out.bezierCount;
    }
  }
  for (uint32_t p = set.bezierCount; p < set.patchCount(); ++p) {
    const auto cp = set.controlPoints(p);
    gregory.points.insert(gregory.points.end(), cp.begin(), cp.end());
    gregory.params.push_back(set.params[p]);
    gregory.origins.push_back(set.origins[p]);
    ++gregory.gregoryCount;
  }
  out.points.insert(out.points.end(), gregory.points.begin(), gregory.points.end());
  out.params.insert(out.params.end(), gregory.params.begin(), gregory.params.end());
  out.origins.insert(out.origins.end(), gregory.origins.begin(), gregory.origins.end());
  out.gregoryCount = gregory.gregoryCount;
  return out;
}

PatchSet concatenate(const PatchSet& a, const PatchSet& b) {
  PatchSet out;
  out.source = a.source + "+" + b.source;
  out.bezierCount = a.bezierCount + b.bezierCount;
  out.gregoryCount = a.gregoryCount + b.gregoryCount;
  auto appendRange = [&](const PatchSet& s, uint32_t first, uint32_t last) {
    for (uint32_t p = first; p < last; ++p) {
      const auto cp = s.controlPoints(p);
      out.points.insert(out.points.end(), cp.begin(), cp.end());
      out.params.push_back(s.params[p]);
      out.origins.push_back(s.origins[p]);
    }
  };
  appendRange(a, 0, a.bezierCount);
  appendRange(b, 0, b.bezierCount);
  appendRange(a, a.bezierCount, a.patchCount());
  appendRange(b, b.bezierCount, b.patchCount());
  return out;
}

PatchSet translated(PatchSet set, const glm::dvec3& offset) {
  for (auto& p : set.points) p += offset;
  return set;
}

PatchSet bezierSphere(const glm::dvec3& center, double radius, uint32_t k) {
  if (k == 0) throw Error("bezierSphere: k must be positive");
  // Cube face f: point = n + a * s + b * t, a, b in [-1, 1]; (s, t, n) right-handed so
  // that dP/du x dP/dv points outwards.
  const glm::dvec3 axes[6][3] = {
      {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}}, {{0, 0, 1}, {0, 1, 0}, {-1, 0, 0}},
      {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}, {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}},
      {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}}};
  const uint32_t n = 3 * k;  // grid intervals per face side
  std::vector<Patch16> patches;
  for (const auto& f : axes) {
    for (uint32_t pj = 0; pj < k; ++pj)
      for (uint32_t pi = 0; pi < k; ++pi) {
        Patch16 p{};
        for (int j = 0; j < 4; ++j)
          for (int i = 0; i < 4; ++i) {
            // Integer grid coordinates make shared points identical across faces: a point
            // on a cube edge has the same (x, y, z) whichever face computes it.
            const double a = -1.0 + 2.0 * double(3 * pi + i) / double(n);
            const double b = -1.0 + 2.0 * double(3 * pj + j) / double(n);
            const glm::dvec3 q = f[2] + a * f[0] + b * f[1];
            p[4 * j + i] = center + radius * glm::normalize(q);
          }
        patches.push_back(p);
      }
  }
  return bezierPatchSet(patches, "built-in:bezier-sphere");
}

PatchSet bsplineTorus(const TorusOptions& o) {
  if (o.nu < 3 || o.nv < 3) throw Error("bsplineTorus: need at least 3 x 3 patches");
  const uint32_t nu = o.nu, nv = o.nv;
  auto control = [&](int i, int j) {
    const uint32_t ii = static_cast<uint32_t>((i % int(nu) + int(nu)) % int(nu));
    const uint32_t jj = static_cast<uint32_t>((j % int(nv) + int(nv)) % int(nv));
    const double theta = 2.0 * glm::pi<double>() * ii / nu;
    const double phi = 2.0 * glm::pi<double>() * jj / nv;
    const double ring = o.majorRadius + o.minorRadius * std::cos(phi);
    return o.center + glm::dvec3(ring * std::cos(theta), ring * std::sin(theta),
                                 o.minorRadius * std::sin(phi));
  };
  // Uniform cubic B-spline to Bézier: bez = M * cv, per direction.
  const double M[4][4] = {{1.0 / 6, 4.0 / 6, 1.0 / 6, 0},
                          {0, 4.0 / 6, 2.0 / 6, 0},
                          {0, 2.0 / 6, 4.0 / 6, 0},
                          {0, 1.0 / 6, 4.0 / 6, 1.0 / 6}};
  std::vector<Patch16> patches(size_t{nu} * nv);
  for (uint32_t pj = 0; pj < nv; ++pj)
    for (uint32_t pi = 0; pi < nu; ++pi) {
      Patch16& bez = patches[pj * nu + pi];
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
          glm::dvec3 sum(0.0);
          for (int l = 0; l < 4; ++l)
            for (int k = 0; k < 4; ++k)
              sum += M[i][k] * M[j][l] * control(int(pi) + k - 1, int(pj) + l - 1);
          bez[4 * j + i] = sum;
        }
    }
  PatchSet set = bezierPatchSet(patches, "built-in:bspline-torus");
  if (o.refinePatch < 0) return set;
  const uint32_t r = static_cast<uint32_t>(o.refinePatch);
  if (r >= patches.size()) throw Error("bsplineTorus: refinePatch out of range");
  const uint32_t ri = r % nu, rj = r / nu;
  // Transition bits of the neighbours on the edge they share with patch r
  // (Far edge order: 0 v=0, 1 u=1, 2 v=1, 3 u=0).
  std::vector<unsigned short> transition(patches.size(), 0);
  transition[rj * nu + (ri + 1) % nu] |= 8;         // right neighbour: its u=0 edge
  transition[rj * nu + (ri + nu - 1) % nu] |= 2;    // left neighbour: its u=1 edge
  transition[((rj + 1) % nv) * nu + ri] |= 1;       // upper neighbour: its v=0 edge
  transition[((rj + nv - 1) % nv) * nu + ri] |= 4;  // lower neighbour: its v=1 edge
  std::vector<Patch16> out;
  PatchSet result;
  result.source = set.source + "+refined";
  for (uint32_t p = 0; p < patches.size(); ++p) {
    if (p == r) {
      const auto children = splitQuarters(patches[p]);
      for (int c = 0; c < 4; ++c) {
        result.points.insert(result.points.end(), children[c].begin(), children[c].end());
        result.params.push_back(makeParam(p, c & 1, c >> 1, 1, 0));
        result.origins.push_back(PatchOrigin::Input);
      }
    } else {
      result.points.insert(result.points.end(), patches[p].begin(), patches[p].end());
      result.params.push_back(makeParam(p, 0, 0, 0, transition[p]));
      result.origins.push_back(PatchOrigin::Input);
    }
  }
  result.bezierCount = static_cast<uint32_t>(result.params.size());
  return result;
}

}  // namespace osd_cull::scene
