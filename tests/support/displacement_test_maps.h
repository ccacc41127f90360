#pragma once
/// \file displacement_test_maps.h
/// \brief The extreme displacement maps every displaced-bound test runs: a single spike, a
/// step, all-max, all-min and scale 0 (issue 11).

#include "osd_cull/bound/displaced_map.h"
#include "osd_cull/patch/cage_mesh.h"

#include <vector>

namespace osd_cull::test {

/// \brief spike (one texel at 1 in 0.5, scale `scale`), step (0 | 1 halves), all-max,
/// all-min, scale-0 (the step with scale 0); midlevel 0.5.
std::vector<bound::DisplacementMap> extremeDisplacementMaps(double scale);

/// \brief `cage` with one UV per vertex, its x and y mapped onto [0, 1]² over the cage's
/// bounding box (a planar projection: continuous everywhere, so no UV seams), for meshes
/// built without texture coordinates.
CageMesh withPlanarUVs(CageMesh cage);

}  // namespace osd_cull::test
