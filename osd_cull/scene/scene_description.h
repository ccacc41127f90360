#pragma once
/// \file scene_description.h
/// \brief What a scene file says (docs/scene-format.md), as plain data: meshes, instances
/// (a mesh, a transform, an optional rigid animation, a time offset), triangle occluders,
/// views (a camera or a camera path, several per frame), the frame range and rate.
///
/// Parsing lives in adapters/scene_file.h (the library proper never parses files); loading
/// the meshes in adapters/scene_assets.h; evaluating transforms and cameras at a time in
/// scene/scene_eval.h. The layout follows RTXMG's .scene.json where it fits: its `models`
/// are our `meshes`, its `graph` nodes our `instances`, its `view` our `views`, and its
/// `settings` our `settings`.

#include "osd_cull/bound/displaced_bounds.h"
#include "osd_cull/patch/adaptive_patches.h"
#include "osd_cull/patch/cage_mesh.h"
#include "osd_cull/scene/cage_animation.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace osd_cull::scene {

/// \brief The scene-file version this build reads.
inline constexpr int kSceneFormatVersion = 1;

/// \brief Where a mesh's motion comes from (scene/cage_animation.h).
struct AnimationSource {
  enum class Kind { None, Twist, Bend, Wave, Skin, Sequence };
  Kind kind = Kind::None;
  DeformerParams deformer;        ///< twist, bend, wave
  SkinningParams skinning;        ///< skin
  std::string pattern;            ///< sequence: file pattern (absolute after parsing)
  double framesPerSecond = 24.0;  ///< sequence: rate of its key frames
};

/// \brief "none", "twist", "bend", "wave", "skin", "sequence".
const char* toString(AnimationSource::Kind kind);

/// \brief A mesh's scalar displacement P + N · scale · (D(s,t) − midlevel) and the displaced
/// bound its culls test: the scene-file form of the `render`/`verify` options
/// --displacement ... --displaced-box (docs/algorithms/displacement.md; Niessner & Loop
/// §4.2, Sathe's per-patch extents).
struct DisplacementDescription {
  std::string source;  ///< absolute path of a PNG or EXR map, or "procedural"
  double scale = 1.0;
  std::optional<double> midlevel;  ///< unset: 0.5 for PNG and procedural, 0 for EXR
  char channel = 'r';              ///< 'r', 'g', 'b' or 'a'
  uint32_t maxLod = 0;             ///< coarsest mip level the draw samples
  bound::DisplacedExtension extension = bound::DisplacedExtension::ACoN;
  bound::DisplacedBox box = bound::DisplacedBox::CAF;
};

/// \brief One subdivision mesh: a cage file or a built-in cage, refined with `patches`.
struct MeshDescription {
  std::string name;
  std::string file;     ///< absolute path; empty for a built-in cage
  std::string builtIn;  ///< scene/procedural.h builtInMesh() name; empty for a file
  std::optional<Scheme> scheme;
  PatchOptions patches;  ///< isolation level, end caps
  AnimationSource animation;
  /// Displaced meshes are static (a deforming mesh's per-frame bounds pass has no displaced
  /// bounds yet); back-patch culling is off for them.
  std::optional<DisplacementDescription> displacement;
  /// Move the cage's bounding-box centre to the origin at load and put the offset into
  /// every instance's transform, so control points stay small (large coordinates).
  bool recentre = true;
};

/// \brief A rigid animation of an instance: a spin about an axis through its origin, then
/// a linear path through translation key frames (either may be absent).
struct InstanceMotion {
  glm::dvec3 spinAxis{0.0, 0.0, 1.0};
  double spinDegreesPerSecond = 0.0;
  struct Key {
    double time = 0.0;  ///< seconds, strictly increasing
    glm::dvec3 translate{0.0};
  };
  std::vector<Key> keys;  ///< clamped outside [first, last]
};

/// \brief A placed mesh. Several instances of one mesh share its control points (unless
/// the mesh deforms and their time offsets differ).
struct InstanceDescription {
  std::string name;
  size_t mesh = 0;               ///< index into SceneDescription::meshes
  std::optional<size_t> parent;  ///< an instance whose transform this one is relative to
  glm::dmat4 transform{1.0};     ///< relative to the parent (or the world)
  InstanceMotion motion;
  double timeOffsetSeconds = 0.0;  ///< added to the scene time for the mesh's deformation
};

/// \brief A triangle occluder: an OBJ file or a box, in world coordinates after `transform`.
struct OccluderDescription {
  std::string file;  ///< absolute path; empty for a box
  glm::dvec3 boxMin{0.0};
  glm::dvec3 boxMax{0.0};
  glm::dmat4 transform{1.0};
};

/// \brief One view rendered every frame. A perspective camera (eye, target, up, fovy),
/// optionally moved by an orbit or camera key frames; or a shadow-map view: an orthographic
/// camera looking along `lightDirection` that frames the whole scene.
struct ViewDescription {
  std::string name;
  enum class Kind { Perspective, Shadow };
  Kind kind = Kind::Perspective;
  glm::dvec3 eye{0.0, -6.0, 3.0};
  glm::dvec3 target{0.0};
  glm::dvec3 up{0.0, 0.0, 1.0};
  double fovyDegrees = 40.0;
  std::optional<double> zNear;  ///< absent: fitted to the scene bounds each frame
  std::optional<double> zFar;
  /// Orbit: the camera turns about the axis `up` through `target` by this many degrees
  /// per second.
  double orbitDegreesPerSecond = 0.0;
  struct Key {
    double time = 0.0;  ///< seconds, strictly increasing
    glm::dvec3 eye{0.0};
    glm::dvec3 target{0.0};
  };
  std::vector<Key> keys;  ///< non-empty: eye and target interpolate linearly (clamped)
  glm::dvec3 lightDirection{0.0, 0.0, -1.0};  ///< shadow: direction the light travels
  uint32_t width = 0;                         ///< 0: SceneSettings::width
  uint32_t height = 0;
};

/// \brief Frame range, rate and image size.
struct SceneSettings {
  uint32_t frameStart = 0;
  uint32_t frameCount = 1;
  double framesPerSecond = 24.0;
  uint32_t width = 640;
  uint32_t height = 480;
  /// Seconds of frame f: f / framesPerSecond.
  double seconds(uint32_t frame) const { return double(frame) / framesPerSecond; }
};

/// \brief A whole scene file.
struct SceneDescription {
  int version = kSceneFormatVersion;
  std::string source;  ///< the file it came from, or "built-in:..."
  std::vector<MeshDescription> meshes;
  std::vector<InstanceDescription> instances;
  std::vector<OccluderDescription> occluders;
  std::vector<ViewDescription> views;
  SceneSettings settings;
};

/// \brief A transform from translate, rotate (Euler angles in degrees, applied x, then y,
/// then z) and scale: T · Rz · Ry · Rx · S.
glm::dmat4 composeTransform(const glm::dvec3& translate, const glm::dvec3& rotateDegrees,
                            const glm::dvec3& scale);

}  // namespace osd_cull::scene
