#pragma once
/// \file cage_animation.h
/// \brief Where a moving cage's positions come from: procedural deformers (twist, bend,
/// wave, linear-blend skinning) and OBJ sequences. A scene's mesh refers to one of these;
/// the application's own rig instead sets positions through the mesh's cage input API.
///
/// The contract shared by the scene loader (which builds animations from a scene file) and
/// the animation code (which implements them): positions() is a pure function of time, so
/// a player can seek, loop and evaluate frames in any order.

#include "osd_cull/patch/cage_mesh.h"

#include <glm/vec3.hpp>

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace osd_cull::scene {

/// \brief Cage positions as a function of time.
class CageAnimation {
 public:
  virtual ~CageAnimation() = default;
  /// \brief Number of cage vertices every call of positions() writes.
  virtual size_t vertexCount() const = 0;
  /// \brief Writes the cage positions at `seconds` (any real value; sequences clamp or
  /// loop as their options say) into `out` (size vertexCount()).
  /// \throws osd_cull::Error when `out` has the wrong size.
  virtual void positions(double seconds, std::span<glm::dvec3> out) const = 0;
  /// \brief Length of one cycle in seconds (a sequence's duration, a deformer's period).
  virtual double duration() const = 0;
  /// \brief "twist", "bend", "wave", "skin" or "sequence:<pattern>", for printed plans.
  virtual std::string describe() const = 0;
};

/// \brief Parameters of the procedural deformers. `axis` is 0 (x), 1 (y) or 2 (z): the
/// axis along which twist and bend vary and along which the wave travels.
struct DeformerParams {
  int axis = 1;
  double amount = 1.0;     ///< twist: radians per unit length at the peak; bend: radians
                           ///< over the mesh's extent; wave: amplitude / mesh extent
  double frequency = 0.5;  ///< oscillations per second
};

/// \brief The bone layouts of makeSkinning().
enum class SkinningRig {
  /// `joints` bones in a chain along the cage's longest axis, each bending the rest of the
  /// chain about the third axis (forward kinematics), phases a quarter cycle apart: a
  /// tail, a snake, a bending tube.
  Chain,
  /// A limb-like rig for a character standing along its longest axis with arms along the
  /// second-longest: a static torso, two legs swinging about the lateral axis from the hips
  /// in antiphase, two arms swinging about the up axis from the shoulders, each against
  /// its leg (a walk). `joints` is ignored (5 bones).
  Limbs,
};

/// \brief Parameters of the linear-blend skinning rig: bones laid out by `rig`, weights
/// from distance to the bones (1 / (d² + ε²)², normalized, ε = 5% of the largest extent),
/// each bone swinging by up to `swingDegrees` at `frequency` Hz.
struct SkinningParams {
  int joints = 4;
  double swingDegrees = 30.0;
  double frequency = 0.5;
  SkinningRig rig = SkinningRig::Chain;
};

/// \brief The procedural deformers of the rest cage `rest` (positions copied).
/// \throws osd_cull::Error for an empty cage, NaN/Inf positions or bad parameters.
std::unique_ptr<CageAnimation> makeTwist(std::span<const glm::dvec3> rest, const DeformerParams& p);
std::unique_ptr<CageAnimation> makeBend(std::span<const glm::dvec3> rest, const DeformerParams& p);
std::unique_ptr<CageAnimation> makeWave(std::span<const glm::dvec3> rest, const DeformerParams& p);
std::unique_ptr<CageAnimation> makeSkinning(std::span<const glm::dvec3> rest,
                                            const SkinningParams& p);

/// \brief An OBJ sequence and its first frame's cage (faces, tags, UVs).
struct ObjSequence {
  CageMesh firstFrame;
  std::unique_ptr<CageAnimation> animation;
};

/// \brief Loads one OBJ per frame, named by `pattern`: `walk/frame_####.obj` (# = a digit of
/// the zero-padded frame number) or RTXMG's range form `name[0-58].obj`. Positions between
/// key frames are interpolated linearly at `framesPerSecond`.
/// \throws osd_cull::Error naming the file (and line) of a missing frame, a frame whose
/// topology differs from the first, or malformed input.
ObjSequence loadObjSequence(const std::string& pattern, double framesPerSecond = 24.0);

}  // namespace osd_cull::scene
