#pragma once
/// \file tessellator_capture.h
/// \brief Captures the triangles the device's tessellator makes for one quad patch with
/// given levels (equal spacing, the draw shaders' transition-edge remap), in parameter
/// space, through a geometry shader. Used to check bound::triangleShape against the real
/// tessellator.

#include "osd_cull/bound/drawn_triangles.h"
#include "osd_cull/vk/context.h"

#include <glm/vec2.hpp>

#include <array>
#include <memory>
#include <vector>

namespace osd_cull::test {

/// \brief One triangle's parameter-space corners, in the order the tessellator emits them.
using ParamTriangle = std::array<glm::dvec2, 3>;

class TessellatorCapture {
 public:
  /// \brief Needs the geometryShader feature (Context::info().optional.geometryShader).
  explicit TessellatorCapture(vulkan::Context& context);
  ~TessellatorCapture();
  TessellatorCapture(const TessellatorCapture&) = delete;
  TessellatorCapture& operator=(const TessellatorCapture&) = delete;

  /// \brief The triangles of one patch tessellated with `levels` (outer = lo + hi, inner =
  /// the average of opposite outer levels, as shaders/patch/patch.tesc sets them).
  std::vector<ParamTriangle> capture(const bound::QuadTessLevels& levels);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// \brief The shape figures of captured triangles as bound::triangleShape defines them:
/// per triangle the corner with the smallest κ (|d1|_1 + |d2|_1), and that corner's
/// κ |d1|_1 |d2|_1; maximized over the triangles; minEdge the shortest L1 edge.
bound::TriangleShape measuredShape(const std::vector<ParamTriangle>& triangles);

}  // namespace osd_cull::test
