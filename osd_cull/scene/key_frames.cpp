#include "osd_cull/scene/key_frames.h"

#include "osd_cull/error.h"
#include "osd_cull/scene/animation_support.h"

#include <cmath>

namespace osd_cull::scene {
namespace {

class KeyFrames final : public CageAnimation {
 public:
  KeyFrames(std::vector<std::vector<glm::dvec3>> frames, double fps, std::string description)
      : frames_(std::move(frames)), fps_(fps), description_(std::move(description)) {
    const std::string who = "key frames '" + description_ + "'";
    detail::requirePositive(fps, who, "the frame rate");
    if (frames_.empty()) throw Error(who + ": no frames");
    for (size_t f = 0; f < frames_.size(); ++f) {
      if (frames_[f].size() != frames_[0].size())
        throw Error(who + ": frame " + std::to_string(f) + " has " +
                    std::to_string(frames_[f].size()) + " vertices, frame 0 has " +
                    std::to_string(frames_[0].size()));
      detail::checkedExtent(frames_[f], who + " frame " + std::to_string(f));
    }
  }

  size_t vertexCount() const override { return frames_[0].size(); }
  double duration() const override { return static_cast<double>(frames_.size()) / fps_; }
  std::string describe() const override { return description_; }

  void positions(double seconds, std::span<glm::dvec3> out) const override {
    detail::requireOutputSize(out.size(), vertexCount(), description_);
    const double n = static_cast<double>(frames_.size());
    double f = std::fmod(seconds * fps_, n);
    if (f < 0.0) f += n;
    if (!(f < n)) f = 0.0;  // fmod of a value just below a multiple of n rounding up
    const size_t k0 = static_cast<size_t>(f);
    const size_t k1 = (k0 + 1) % frames_.size();
    const double w = f - static_cast<double>(k0);
    const auto& a = frames_[k0];
    const auto& b = frames_[k1];
    for (size_t i = 0; i < out.size(); ++i) out[i] = w == 0.0 ? a[i] : a[i] + w * (b[i] - a[i]);
  }

 private:
  std::vector<std::vector<glm::dvec3>> frames_;
  double fps_;
  std::string description_;
};

}  // namespace

std::unique_ptr<CageAnimation> makeKeyFrameAnimation(std::vector<std::vector<glm::dvec3>> frames,
                                                     double framesPerSecond,
                                                     std::string description) {
  return std::make_unique<KeyFrames>(std::move(frames), framesPerSecond, std::move(description));
}

}  // namespace osd_cull::scene
