#pragma once
/// \file key_frames.h
/// \brief Cage positions given at key frames (an OBJ sequence, a baked cache), linearly
/// interpolated between them. The file reading is in adapters/obj_sequence.h; this is the
/// part that needs no file.

#include "osd_cull/scene/cage_animation.h"

#include <glm/vec3.hpp>

#include <memory>
#include <string>
#include <vector>

namespace osd_cull::scene {

/// \brief An animation through `frames` (each one position per cage vertex) at
/// `framesPerSecond`: at time t the positions blend keys floor(f) and floor(f) + 1 with
/// weight f - floor(f), f = t * framesPerSecond, looping (the last key blends into the
/// first, duration() = frames / framesPerSecond). `description` is returned by describe().
/// \throws osd_cull::Error for no frames, frames of different sizes, an empty frame, a NaN
/// or Inf coordinate (naming the frame and vertex) or a rate that is not finite and > 0.
std::unique_ptr<CageAnimation> makeKeyFrameAnimation(std::vector<std::vector<glm::dvec3>> frames,
                                                     double framesPerSecond,
                                                     std::string description);

}  // namespace osd_cull::scene
