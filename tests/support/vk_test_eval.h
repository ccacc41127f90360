#pragma once
/// \file vk_test_eval.h
/// \brief Double-precision evaluation of Bézier and Gregory-basis patches, written from
/// the formulas (independent of the GLSL under test).

#include "osd_cull/patch/patch_set.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <span>

namespace osd_cull::test {

/// \brief Point of a bicubic Bézier patch (point (i, j) = cp[4j + i]) at (u, v).
glm::dvec3 evalBezier(std::span<const glm::dvec3> cp, double u, double v);

/// \brief Point of a Gregory-basis patch (OpenSubdiv order) at (u, v): the Bézier patch
/// whose interior point at corner c is (w+ Fp + w- Fm) with the rational weights of
/// Loop et al., e.g. corner 0: (u Fp + v Fm) / (u + v).
glm::dvec3 evalGregory(std::span<const glm::dvec3> cp, double u, double v);

/// \brief evalBezier or evalGregory by the patch's type.
glm::dvec3 evalPatch(const PatchSet& set, uint32_t patch, double u, double v);

}  // namespace osd_cull::test
