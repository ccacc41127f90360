// The procedural deformers of cage_animation.h: twist, bend and wave, each a closed-form
// function of the rest position and time with period 1 / frequency, so tests know their
// values and a player can seek anywhere.
#include "osd_cull/error.h"
#include "osd_cull/scene/animation_support.h"
#include "osd_cull/scene/cage_animation.h"

#include <cmath>
#include <numbers>
#include <vector>

namespace osd_cull::scene {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

enum class Kind { Twist, Bend, Wave };

const char* name(Kind k) {
  switch (k) {
    case Kind::Twist:
      return "twist";
    case Kind::Bend:
      return "bend";
    case Kind::Wave:
      return "wave";
  }
  return "?";
}

class Deformer final : public CageAnimation {
 public:
  Deformer(Kind kind, std::span<const glm::dvec3> rest, const DeformerParams& p)
      : kind_(kind), rest_(rest.begin(), rest.end()), p_(p) {
    const std::string who = std::string("make") + (kind == Kind::Twist  ? "Twist"
                                                   : kind == Kind::Bend ? "Bend"
                                                                        : "Wave");
    if (p.axis < 0 || p.axis > 2)
      throw Error(who + ": axis must be 0 (x), 1 (y) or 2 (z), got " + std::to_string(p.axis));
    detail::requireFinite(p.amount, who, "amount");
    detail::requirePositive(p.frequency, who, "frequency");
    extent_ = detail::checkedExtent(rest, who);
    length_ = extent_.size()[p.axis];
    if (!(length_ > 0.0) && kind != Kind::Twist)
      throw Error(who + ": the rest cage has no extent along axis " + std::to_string(p.axis));
  }

  size_t vertexCount() const override { return rest_.size(); }
  double duration() const override { return 1.0 / p_.frequency; }
  std::string describe() const override { return name(kind_); }

  void positions(double seconds, std::span<glm::dvec3> out) const override {
    detail::requireOutputSize(out.size(), rest_.size(), describe());
    const int a = p_.axis, b = (a + 1) % 3, c = (a + 2) % 3;
    const glm::dvec3 centre = extent_.centre();
    // Phase of the cycle; fmod keeps large times as accurate as small ones.
    const double phase = kTwoPi * std::fmod(seconds * p_.frequency, 1.0);
    for (size_t i = 0; i < rest_.size(); ++i) {
      glm::dvec3 q = rest_[i];
      const double s = q[a] - centre[a];
      switch (kind_) {
        case Kind::Twist: {
          // Rotation about the axis line through the centre by amount * s * sin(phase).
          const double angle = p_.amount * s * std::sin(phase);
          const double x = q[b] - centre[b], y = q[c] - centre[c];
          q[b] = centre[b] + x * std::cos(angle) - y * std::sin(angle);
          q[c] = centre[c] + x * std::sin(angle) + y * std::cos(angle);
          break;
        }
        case Kind::Bend: {
          // The axis bends into a circular arc of curvature k = θ / L in the (a, b) plane,
          // θ = amount sin(phase); the centre stays, lengths along the axis are kept.
          const double k = p_.amount * std::sin(phase) / length_;
          if (std::abs(k) * length_ < 1e-12) break;
          const double r = 1.0 / k, x = q[b] - centre[b], t = k * s;
          q[a] = centre[a] + (r - x) * std::sin(t);
          q[b] = centre[b] + r - (r - x) * std::cos(t);
          break;
        }
        case Kind::Wave:
          // A sine wave one mesh length long travelling along the axis, amplitude
          // amount * L across it (axis b).
          q[b] += p_.amount * length_ * std::sin(kTwoPi * s / length_ - phase);
          break;
      }
      out[i] = q;
    }
  }

 private:
  Kind kind_;
  std::vector<glm::dvec3> rest_;
  DeformerParams p_;
  detail::Extent extent_;
  double length_ = 0.0;
};

}  // namespace

std::unique_ptr<CageAnimation> makeTwist(std::span<const glm::dvec3> rest,
                                         const DeformerParams& p) {
  return std::make_unique<Deformer>(Kind::Twist, rest, p);
}
std::unique_ptr<CageAnimation> makeBend(std::span<const glm::dvec3> rest, const DeformerParams& p) {
  return std::make_unique<Deformer>(Kind::Bend, rest, p);
}
std::unique_ptr<CageAnimation> makeWave(std::span<const glm::dvec3> rest, const DeformerParams& p) {
  return std::make_unique<Deformer>(Kind::Wave, rest, p);
}

}  // namespace osd_cull::scene
