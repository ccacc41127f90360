#include "osd_cull/scene/procedural.h"

#include "osd_cull/error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

namespace osd_cull::scene {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// OpenSubdiv's limit on the number of faces or edges around a vertex (Vtr::VALENCE_LIMIT).
constexpr int kMaxValence = (1 << 16) - 1;

void addFace(CageMesh& m, std::initializer_list<int> vertices) {
  m.faceSizes.push_back(static_cast<int>(vertices.size()));
  m.faceVertices.insert(m.faceVertices.end(), vertices);
}

}  // namespace

CageMesh cube() {
  CageMesh m;
  m.source = "built-in:cube";
  m.positions = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  for (auto f : {std::array{0, 3, 2, 1}, std::array{4, 5, 6, 7}, std::array{0, 1, 5, 4},
                 std::array{1, 2, 6, 5}, std::array{2, 3, 7, 6}, std::array{3, 0, 4, 7}})
    addFace(m, {f[0], f[1], f[2], f[3]});
  return m;
}

CageMesh torus(int u, int v, double majorRadius, double minorRadius) {
  if (u < 3 || v < 3 || u > 1 << 12 || v > 1 << 12)
    throw Error("torus: needs 3 <= u, v <= 4096 quads around, got " + std::to_string(u) + " x " +
                std::to_string(v));
  if (!(minorRadius > 0.0 && minorRadius < majorRadius && std::isfinite(majorRadius)))
    throw Error("torus: needs 0 < minor radius < major radius, got " + std::to_string(minorRadius) +
                " and " + std::to_string(majorRadius));
  CageMesh m;
  m.source = "built-in:torus";
  for (int i = 0; i < u; ++i)
    for (int j = 0; j < v; ++j) {
      const double phi = kTwoPi * i / u, theta = kTwoPi * j / v;
      const double ring = majorRadius + minorRadius * std::cos(theta);
      m.positions.emplace_back(ring * std::cos(phi), ring * std::sin(phi),
                               minorRadius * std::sin(theta));
    }
  auto at = [&](int i, int j) { return (i % u) * v + (j % v); };
  // (i, j) → (i+1, j) → (i+1, j+1) → (i, j+1) turns counter-clockwise seen from outside:
  // d/dphi × d/dtheta points away from the tube's centre line.
  for (int i = 0; i < u; ++i)
    for (int j = 0; j < v; ++j)
      addFace(m, {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
  return m;
}

CageMesh poleSphere(int valence, int rings) {
  if (valence < 3 || valence > kMaxValence)
    throw Error("pole sphere: valence must be in [3, " + std::to_string(kMaxValence) + "], got " +
                std::to_string(valence));
  if (rings < 1 || static_cast<int64_t>(rings) * valence > 1 << 24)
    throw Error("pole sphere: needs at least 1 ring and at most 2^24 vertices, got " +
                std::to_string(rings) + " rings");
  const int n = valence;
  CageMesh m;
  m.source = "built-in:pole-sphere-" + std::to_string(n);
  m.positions.emplace_back(0, 0, 1);   // 0: north pole
  m.positions.emplace_back(0, 0, -1);  // 1: south pole
  for (int r = 0; r < rings; ++r)
    for (int k = 0; k < n; ++k) {
      const double theta = std::numbers::pi * (r + 1) / (rings + 1), phi = kTwoPi * k / n;
      m.positions.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                               std::cos(theta));
    }
  auto at = [&](int r, int k) { return 2 + r * n + k % n; };
  for (int k = 0; k < n; ++k) addFace(m, {0, at(0, k), at(0, k + 1)});
  for (int r = 0; r + 1 < rings; ++r)
    for (int k = 0; k < n; ++k)
      addFace(m, {at(r, k), at(r + 1, k), at(r + 1, k + 1), at(r, k + 1)});
  for (int k = 0; k < n; ++k) addFace(m, {1, at(rings - 1, k + 1), at(rings - 1, k)});
  return m;
}

CageMesh creasedCube() {
  CageMesh m = cube();
  m.source = "built-in:creased-cube";
  m.creases = {{4, 5, 2.0f}, {5, 6, 2.0f}, {6, 7, 2.0f}, {7, 4, 2.0f}, {2, 6, 10.0f}};
  m.corners = {{0, 3.0f}};
  return m;
}

CageMesh collapsedFaceCube() {
  CageMesh m = cube();
  m.source = "built-in:collapsed-face";
  m.positions[4] = m.positions[7] = {-1, 0, 1};
  m.positions[5] = m.positions[6] = {1, 0, 1};
  return m;
}

CageMesh defaultMesh() {
  constexpr int k = 4;  // quads along a cube edge
  CageMesh m;
  m.source = "built-in:default";
  // Lattice points (i, j, l) in [0, k]^3 on the cube's surface, shared between faces.
  std::map<std::array<int, 3>, int> index;
  std::vector<std::array<int, 3>> lattice;
  auto vertex = [&](std::array<int, 3> p) {
    auto [it, inserted] = index.try_emplace(p, static_cast<int>(lattice.size()));
    if (inserted) lattice.push_back(p);
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      // (b, c, axis) is right-handed, so b × c points along +axis.
      const int b = (axis + 1) % 3, c = (axis + 2) % 3;
      for (int s = 0; s < k; ++s)
        for (int t = 0; t < k; ++t) {
          auto p = [&](int ds, int dt) {
            std::array<int, 3> q{};
            q[static_cast<size_t>(axis)] = side * k;
            q[static_cast<size_t>(b)] = s + ds;
            q[static_cast<size_t>(c)] = t + dt;
            return vertex(q);
          };
          if (side == 1)
            addFace(m, {p(0, 0), p(1, 0), p(1, 1), p(0, 1)});
          else
            addFace(m, {p(0, 0), p(0, 1), p(1, 1), p(1, 0)});
        }
    }
  for (const auto& q : lattice) {
    const glm::dvec3 box = glm::dvec3(q[0], q[1], q[2]) * (2.0 / k) - 1.0;
    const glm::dvec3 dir = glm::normalize(box);
    // Two thirds of the way to a sphere, with gentle lumps so views differ.
    const double lumps =
        1.0 + 0.08 * std::sin(3.0 * dir.x + 1.0) * std::cos(2.0 * dir.y) + 0.05 * dir.z * dir.x;
    m.positions.push_back(glm::mix(box, dir * 1.25, 2.0 / 3.0) * lumps);
  }
  // The crease loop: edges between neighbouring lattice points on the middle layer l = k/2.
  std::set<std::pair<int, int>> crease;
  for (size_t f = 0; f < m.faceSizes.size(); ++f)
    for (size_t e = 0; e < 4; ++e) {
      const int a = m.faceVertices[4 * f + e], bb = m.faceVertices[4 * f + (e + 1) % 4];
      if (lattice[static_cast<size_t>(a)][2] == k / 2 &&
          lattice[static_cast<size_t>(bb)][2] == k / 2)
        crease.insert({std::min(a, bb), std::max(a, bb)});
    }
  for (const auto& [a, bb] : crease) m.creases.push_back({a, bb, 2.0f});
  return m;
}

std::vector<std::string> builtInMeshNames() {
  return {"cube",           "torus",   "pole-sphere-<n>", "creased-cube",
          "collapsed-face", "default", "character"};
}

std::optional<CageMesh> builtInMesh(std::string_view name) {
  if (name.starts_with("built-in:")) name.remove_prefix(9);
  if (name == "cube") return cube();
  if (name == "torus") return torus();
  if (name == "creased-cube") return creasedCube();
  if (name == "collapsed-face") return collapsedFaceCube();
  if (name == "default") return defaultMesh();
  if (name == "character") return character();
  if (name.starts_with("pole-sphere-")) {
    const std::string_view digits = name.substr(12);
    int n = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
    if (ec == std::errc() && end == digits.data() + digits.size() && n >= 3 && n <= kMaxValence)
      return poleSphere(n);
  }
  return std::nullopt;
}

void translate(CageMesh& mesh, const glm::dvec3& offset) {
  for (glm::dvec3& p : mesh.positions) p += offset;
}

void scale(CageMesh& mesh, const glm::dvec3& factors) {
  for (glm::dvec3& p : mesh.positions) p *= factors;
  if (factors.x * factors.y * factors.z >= 0.0) return;
  // A mirror turns faces inside out; reverse each face (keeping its first vertex) to undo it.
  size_t offset = 0;
  for (int n : mesh.faceSizes) {
    std::reverse(
        mesh.faceVertices.begin() + static_cast<std::ptrdiff_t>(offset + 1),
        mesh.faceVertices.begin() + static_cast<std::ptrdiff_t>(offset + static_cast<size_t>(n)));
    offset += static_cast<size_t>(n);
  }
}

}  // namespace osd_cull::scene
