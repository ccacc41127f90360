#include "osd_cull/scene/scene_eval.h"

#include "osd_cull/error.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace osd_cull::scene {

namespace {

// Linear interpolation through key frames, clamped outside them.
template <class Key, class Get>
glm::dvec3 interpolate(const std::vector<Key>& keys, double t, Get get) {
  if (t <= keys.front().time) return get(keys.front());
  if (t >= keys.back().time) return get(keys.back());
  const auto next = std::upper_bound(keys.begin(), keys.end(), t,
                                     [](double v, const Key& k) { return v < k.time; });
  const Key& b = *next;
  const Key& a = *(next - 1);
  const double s = (t - a.time) / (b.time - a.time);
  return get(a) + s * (get(b) - get(a));
}

glm::dmat4 ownMatrix(const InstanceDescription& inst, double seconds) {
  glm::dmat4 m = inst.transform;
  const InstanceMotion& mo = inst.motion;
  if (mo.spinDegreesPerSecond != 0.0)
    m = m * glm::rotate(glm::dmat4(1.0), glm::radians(mo.spinDegreesPerSecond * seconds),
                        glm::normalize(mo.spinAxis));
  if (!mo.keys.empty())
    m = glm::translate(glm::dmat4(1.0),
                       interpolate(mo.keys, seconds, [](const auto& k) { return k.translate; })) *
        m;
  return m;
}

}  // namespace

const char* toString(AnimationSource::Kind kind) {
  switch (kind) {
    case AnimationSource::Kind::Twist:
      return "twist";
    case AnimationSource::Kind::Bend:
      return "bend";
    case AnimationSource::Kind::Wave:
      return "wave";
    case AnimationSource::Kind::Skin:
      return "skin";
    case AnimationSource::Kind::Sequence:
      return "sequence";
    default:
      return "none";
  }
}

glm::dmat4 composeTransform(const glm::dvec3& translate, const glm::dvec3& rotateDegrees,
                            const glm::dvec3& scale) {
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), translate);
  m = glm::rotate(m, glm::radians(rotateDegrees.z), glm::dvec3(0, 0, 1));
  m = glm::rotate(m, glm::radians(rotateDegrees.y), glm::dvec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(rotateDegrees.x), glm::dvec3(1, 0, 0));
  return glm::scale(m, scale);
}

glm::dmat4 instanceMatrix(const SceneDescription& scene, size_t index, double seconds) {
  glm::dmat4 m(1.0);
  size_t steps = 0;
  for (std::optional<size_t> i = index; i; i = scene.instances[*i].parent) {
    if (*i >= scene.instances.size())
      throw Error("scene " + scene.source + ": instance " + std::to_string(*i) + " does not exist");
    if (++steps > scene.instances.size())
      throw Error("scene " + scene.source + ": instance '" + scene.instances[index].name +
                  "' is its own ancestor (parent cycle)");
    m = ownMatrix(scene.instances[*i], seconds) * m;
  }
  return m;
}

std::vector<glm::dmat4> instanceMatrices(const SceneDescription& scene, double seconds) {
  std::vector<glm::dmat4> out;
  for (size_t i = 0; i < scene.instances.size(); ++i)
    out.push_back(instanceMatrix(scene, i, seconds));
  return out;
}

frame::Bounds worldBounds(std::span<const frame::Bounds> objectBounds,
                          std::span<const glm::dmat4> models) {
  std::vector<glm::dvec3> corners;
  for (size_t i = 0; i < objectBounds.size() && i < models.size(); ++i)
    for (int c = 0; c < 8; ++c) {
      const frame::Bounds& b = objectBounds[i];
      const glm::dvec3 p((c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y,
                         (c & 4) ? b.hi.z : b.lo.z);
      corners.push_back(glm::dvec3(models[i] * glm::dvec4(p, 1.0)));
    }
  return frame::boundsOf(corners);
}

frame::Camera viewCamera(const ViewDescription& view, const SceneSettings& settings,
                         const frame::Bounds& sceneBounds, double seconds) {
  const uint32_t w = view.width ? view.width : settings.width;
  const uint32_t h = view.height ? view.height : settings.height;
  const double r = std::max(sceneBounds.radius(), 1e-9);
  const glm::dvec3 c = sceneBounds.center();
  if (view.kind == ViewDescription::Kind::Shadow) {
    // An orthographic view along the light that contains the scene's bounding sphere.
    const glm::dvec3 d = glm::normalize(view.lightDirection);
    const glm::dvec3 up = std::abs(glm::dot(d, view.up)) < 0.999 * glm::length(view.up)
                              ? view.up
                              : glm::dvec3(1, 0, 0);
    const glm::dvec3 eye = c - d * (2.0 * r);
    const double aspect = double(w) / double(h);
    const double half = aspect >= 1.0 ? r : r / aspect;
    return frame::Camera::orthographic(glm::lookAt(eye, c, up), -half * aspect, half * aspect,
                                       -half, half, r, 3.0 * r, w, h);
  }
  glm::dvec3 eye = view.eye, target = view.target;
  if (!view.keys.empty()) {
    eye = interpolate(view.keys, seconds, [](const auto& k) { return k.eye; });
    target = interpolate(view.keys, seconds, [](const auto& k) { return k.target; });
  }
  if (view.orbitDegreesPerSecond != 0.0) {
    const glm::dmat4 turn =
        glm::rotate(glm::dmat4(1.0), glm::radians(view.orbitDegreesPerSecond * seconds),
                    glm::normalize(view.up));
    eye = target + glm::dvec3(turn * glm::dvec4(eye - target, 0.0));
  }
  const double d = glm::distance(eye, c);
  const double zNear = view.zNear.value_or(std::max(d - r, (d + r) * 1e-4));
  const double zFar = view.zFar.value_or(d + r);
  return frame::Camera::lookAt(eye, target, view.up, view.fovyDegrees, w, h, zNear, zFar);
}

}  // namespace osd_cull::scene
