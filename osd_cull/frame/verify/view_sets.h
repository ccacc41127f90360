#pragma once
/// \file view_sets.h
/// \brief Random camera sets for measuring cull rates (osd-cull verify, tests, benchmarks).
///
/// Both sets keep the object's whole bounding sphere (centre of its bounding box, radius r =
/// half the box diagonal) inside the view, with a random roll:
/// - Sphere: the eye on a sphere of radius R = r / sin(θ/2) around the centre (θ = the
///   smaller of the horizontal and vertical field of view; R = 2.92 r for the default 40°
///   on a landscape image), uniformly distributed over the sphere, looking at the centre.
///   This is the back-patch paper's setting (Loop et al. §7, "10 k random views"; the
///   paper gives no radius): the bounding sphere just fits the view.
/// - WholeObject: a uniform random direction, a distance uniform in [R, 2R], and the view
///   direction turned away from the centre by a random angle that still keeps the bounding
///   sphere in view (the occlusion paper's "whole object" views).
/// Near and far planes enclose the bounding sphere: near = (d - r) / 2, far = d + 1.5 r.

#include "osd_cull/frame/camera.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace osd_cull::frame {

enum class ViewSet { Sphere, WholeObject };

/// \brief "sphere", "whole-object".
const char* toString(ViewSet set);
/// \brief Parses toString()'s names. \throws osd_cull::Error for others.
ViewSet parseViewSet(std::string_view name);

/// \brief Options of randomViews().
struct ViewSetOptions {
  ViewSet set = ViewSet::Sphere;
  uint32_t count = 100;
  uint64_t seed = 1;
  uint32_t width = 256;
  uint32_t height = 256;
  double fovyDegrees = 40.0;
};

/// \brief `count` random views of `bounds` (same seed, same views).
std::vector<Camera> randomViews(const Bounds& bounds, const ViewSetOptions& options);

}  // namespace osd_cull::frame
