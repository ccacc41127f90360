// Linear-blend skinning (cage_animation.h makeSkinning): a few rigid bones, each vertex
// moved by the weighted sum of its bones' transforms, p' = Σ_b w_b M_b(t) p, with weights
// from the distance of the rest vertex to each bone segment. A simple stand-in for a real
// rig: smooth, periodic, and with the local stretching and folding at joints that makes
// bounds built once go stale.
#include "osd_cull/error.h"
#include "osd_cull/scene/animation_support.h"
#include "osd_cull/scene/cage_animation.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace osd_cull::scene {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kMaxJoints = 64;

// A bone: a rest segment (for the weights) and its motion, a rotation about `rotationAxis`
// through `pivot` by amplitude * sin(phase + phaseOffset), applied after its parent's.
struct Bone {
  glm::dvec3 a{0.0}, b{0.0};
  int parent = -1;
  glm::dvec3 pivot{0.0};
  glm::dvec3 rotationAxis{0.0, 0.0, 1.0};
  double amplitude = 0.0;  // radians
  double phaseOffset = 0.0;
};

double segmentDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

glm::dvec3 unit(int axis) {
  glm::dvec3 v(0.0);
  v[axis] = 1.0;
  return v;
}

std::vector<Bone> chainRig(const detail::Extent& e, int joints, double swing) {
  const glm::dvec3 size = e.size();
  const int a = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
  const int c = (a + 2) % 3;
  std::vector<Bone> bones(static_cast<size_t>(joints));
  for (int k = 0; k < joints; ++k) {
    Bone& bone = bones[static_cast<size_t>(k)];
    bone.a = bone.b = e.centre();
    bone.a[a] = e.lo[a] + size[a] * k / joints;
    bone.b[a] = e.lo[a] + size[a] * (k + 1) / joints;
    bone.parent = k - 1;
    bone.pivot = bone.a;
    bone.rotationAxis = unit(c);
    bone.amplitude = swing;
    bone.phaseOffset = 0.5 * std::numbers::pi * k;
  }
  return bones;
}

std::vector<Bone> limbRig(const detail::Extent& e, double swing) {
  const glm::dvec3 size = e.size(), mid = e.centre();
  int up = 0;
  for (int i = 1; i < 3; ++i)
    if (size[i] > size[up]) up = i;
  int lateral = (up + 1) % 3;
  if (size[(up + 2) % 3] > size[lateral]) lateral = (up + 2) % 3;
  auto at = [&](double lateralShare, double height) {  // a point of the mid plane
    glm::dvec3 p = mid;
    p[lateral] = mid[lateral] + lateralShare * size[lateral];
    p[up] = e.lo[up] + height * size[up];
    return p;
  };
  std::vector<Bone> bones;
  bones.push_back({at(0, 0.35), at(0, 0.85), -1, mid, unit(up), 0.0, 0.0});  // torso
  for (int side = -1; side <= 1; side += 2) {
    const glm::dvec3 hip = at(0.15 * side, 0.4);
    bones.push_back({hip, at(0.15 * side, 0.0), 0, hip, unit(lateral), swing * side, 0.0});
    const glm::dvec3 shoulder = at(0.2 * side, 0.7);
    bones.push_back({shoulder, at(0.5 * side, 0.7), 0, shoulder, unit(up), swing * side, 0.0});
  }
  return bones;
}

class Skinning final : public CageAnimation {
 public:
  Skinning(std::span<const glm::dvec3> rest, const SkinningParams& p)
      : rest_(rest.begin(), rest.end()), p_(p) {
    const std::string who = "makeSkinning";
    detail::requireFinite(p.swingDegrees, who, "swingDegrees");
    detail::requirePositive(p.frequency, who, "frequency");
    if (p.rig == SkinningRig::Chain && (p.joints < 1 || p.joints > kMaxJoints))
      throw Error(who + ": joints must be in [1, " + std::to_string(kMaxJoints) + "], got " +
                  std::to_string(p.joints));
    const detail::Extent e = detail::checkedExtent(rest, who);
    const double swing = p.swingDegrees * std::numbers::pi / 180.0;
    bones_ = p.rig == SkinningRig::Chain ? chainRig(e, p.joints, swing) : limbRig(e, swing);
    const glm::dvec3 size = e.size();
    const double eps = 0.05 * std::max({size.x, size.y, size.z, 1e-300});
    weights_.resize(rest_.size() * bones_.size());
    for (size_t v = 0; v < rest_.size(); ++v) {
      double sum = 0.0;
      for (size_t b = 0; b < bones_.size(); ++b) {
        const double d = segmentDistance(rest_[v], bones_[b].a, bones_[b].b) / eps;
        const double w = 1.0 / ((d * d + 1.0) * (d * d + 1.0));
        weights_[v * bones_.size() + b] = w;
        sum += w;
      }
      for (size_t b = 0; b < bones_.size(); ++b) weights_[v * bones_.size() + b] /= sum;
    }
  }

  size_t vertexCount() const override { return rest_.size(); }
  double duration() const override { return 1.0 / p_.frequency; }
  std::string describe() const override { return "skin"; }

  void positions(double seconds, std::span<glm::dvec3> out) const override {
    detail::requireOutputSize(out.size(), rest_.size(), "skin");
    const double phase = kTwoPi * std::fmod(seconds * p_.frequency, 1.0);
    // Forward kinematics in rest coordinates: M_b = M_parent T(pivot) R(θ) T(-pivot).
    std::vector<glm::dmat4> m(bones_.size(), glm::dmat4(1.0));
    for (size_t b = 0; b < bones_.size(); ++b) {
      const Bone& bone = bones_[b];
      const double angle = bone.amplitude * std::sin(phase + bone.phaseOffset);
      glm::dmat4 local = glm::translate(glm::dmat4(1.0), bone.pivot);
      local = glm::rotate(local, angle, bone.rotationAxis);
      local = glm::translate(local, -bone.pivot);
      m[b] = bone.parent >= 0 ? m[static_cast<size_t>(bone.parent)] * local : local;
    }
    for (size_t v = 0; v < rest_.size(); ++v) {
      const glm::dvec4 p(rest_[v], 1.0);
      glm::dvec3 q(0.0);
      for (size_t b = 0; b < bones_.size(); ++b)
        q += weights_[v * bones_.size() + b] * glm::dvec3(m[b] * p);
      out[v] = q;
    }
  }

 private:
  std::vector<glm::dvec3> rest_;
  SkinningParams p_;
  std::vector<Bone> bones_;
  std::vector<double> weights_;  // vertex-major, one per bone
};

}  // namespace

std::unique_ptr<CageAnimation> makeSkinning(std::span<const glm::dvec3> rest,
                                            const SkinningParams& p) {
  return std::make_unique<Skinning>(rest, p);
}

}  // namespace osd_cull::scene
