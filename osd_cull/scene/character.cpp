// scene::character(): a blocky figure built from voxels, whose boundary quads form a closed,
// outward-oriented cage; Catmull-Clark rounds it into a gingerbread-like character.
#include "osd_cull/scene/procedural.h"

#include <array>
#include <map>
#include <set>

namespace osd_cull::scene {

namespace {

using Cell = std::array<int, 3>;

// The figure in cells (x across, y depth, z up), one cell deep: legs, torso, arms held out
// at shoulder height, head. No two filled cells touch only along an edge, so the boundary is
// a manifold.
std::set<Cell> figureCells() {
  std::set<Cell> cells;
  for (int z = 0; z < 3; ++z) cells.insert({{1, 0, z}}), cells.insert({{3, 0, z}});  // legs
  for (int z = 3; z < 6; ++z)
    for (int x = 1; x <= 3; ++x) cells.insert({{x, 0, z}});  // torso
  for (int x : {-1, 0, 4, 5}) cells.insert({{x, 0, 5}});     // arms
  cells.insert({{2, 0, 6}});                                 // head
  cells.insert({{2, 0, 7}});
  return cells;
}

}  // namespace

CageMesh character() {
  const std::set<Cell> cells = figureCells();
  CageMesh m;
  m.source = "built-in:character";
  std::map<Cell, int> index;
  // Cell size: 0.3 across and up, 0.45 deep; feet on z = 0, centred in x and y.
  auto vertex = [&](const Cell& c) {
    auto [it, added] = index.emplace(c, static_cast<int>(m.positions.size()));
    if (added) m.positions.push_back({0.3 * (c[0] - 2.5), 0.45 * (c[1] - 0.5), 0.3 * c[2]});
    return it->second;
  };
  for (const Cell& c : cells)
    for (int axis = 0; axis < 3; ++axis)
      for (int sign : {-1, 1}) {
        Cell n = c;
        n[size_t(axis)] += sign;
        if (cells.count(n)) continue;
        // The quad on this side, counter-clockwise seen from outside: for the outward normal
        // +e_a the order base, base + e_u, base + e_u + e_v, base + e_v has normal e_u x e_v.
        const size_t a = size_t(axis), u = (a + 1) % 3, v = (a + 2) % 3;
        Cell base = c;
        if (sign > 0) base[a] += 1;
        Cell bu = base, buv = base, bv = base;
        bu[u] += 1;
        buv[u] += 1;
        buv[v] += 1;
        bv[v] += 1;
        const std::array<Cell, 4> quad = sign > 0 ? std::array<Cell, 4>{base, bu, buv, bv}
                                                  : std::array<Cell, 4>{base, bv, buv, bu};
        m.faceSizes.push_back(4);
        for (const Cell& q : quad) m.faceVertices.push_back(vertex(q));
      }
  return m;
}

}  // namespace osd_cull::scene
