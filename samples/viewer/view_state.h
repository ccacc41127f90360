#pragma once
/// \file view_state.h
/// \brief What the viewer shows and culls, the keys that change it (in the habit of
/// OpenSubdiv's glViewer), and the `--script` language that presses them, with no window
/// or device: the window feeds keys in, the frame loop reads the state out.

#include "osd_cull/error.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace osd_cull::viewer {

/// \brief Everything a key can change.
struct ViewState {
  uint32_t tessLevel = 4;  ///< uniform tessellation level
  bool adaptive = false;   ///< screen-space adaptive tessellation instead
  double pixelsPerSegment = 8.0;
  uint32_t maxTessLevel = 64;

  /// The effect plan chooses the cull stages each frame (key p; a stage key takes manual
  /// control). Only where the viewer has a planner (a calibration of the device).
  bool plan = false;
  bool frustum = false;  ///< cull stages, when the plan is off
  bool backPatch = false;
  bool occlusion = false;
  std::string backPatchMethod = "tcone";

  bool statusColors = false;  ///< color patches by cull status (needs a cull stage)
  bool typeColors = false;    ///< regular / boundary / corner / Gregory
  bool wireframe = false;
  bool playing = false;      ///< the scene's animations advance one frame per frame drawn
  uint32_t sceneFrame = 0;   ///< the animation frame shown, from the scene's first frame
  bool turntable = false;    ///< the orbit camera turns about the up axis
  bool sceneCamera = false;  ///< look through the scene's camera (its path) instead of orbiting
  bool freezeCull = false;   ///< keep the cull camera; fly around what it culled
  bool showHud = true;
  bool quit = false;

  double yawDegrees = 0.0;    ///< camera orbit about the up axis
  double pitchDegrees = 0.0;  ///< and about the camera's right axis, in [-85, 85]
  double zoom = 1.0;          ///< eye distance scale, in [0.05, 20]
  /// Pan of the orbit pivot along the view's right and up axes (middle drag, as in
  /// OpenSubdiv's glViewer), in units of the framed bounding radius, each in [-4, 4].
  double panX = 0.0, panY = 0.0;

  bool anyCull() const { return frustum || backPatch || occlusion; }
  /// \brief "plan", "frustum+backpatch(tcone)+hiz", or "none".
  std::string cullLabel() const;
};

/// \brief When the viewer draws a timed diagnostic frame (CullFrameOptions::timePasses:
/// each pass submitted, waited for and timed with the wall clock) to show ms per pass,
/// and the figures of the last one. The normal frame is one submission and has no split.
class PassTiming {
 public:
  explicit PassTiming(uint32_t interval = 30) : interval_(interval) {}
  /// \brief Frames between timed frames; 0: never.
  uint32_t interval() const { return interval_; }
  /// \brief True when frame `frame` should be timed: no timed frame since the cull frame
  /// was made (forget()) and `frame` is not the frame that made it (its pipelines and
  /// passes are built then: one-off work that is no pass's time), or `interval` frames
  /// since the last one.
  bool due(uint32_t frame) const;
  /// \brief Keeps the figures of timed frame `frame`.
  void record(uint32_t frame, double pass1Ms, double pyramidMs, double cullMs, double pass2Ms);
  /// \brief Drops the figures: the cull frame they were measured on is gone; a new one is
  /// made at frame `madeAt`.
  void forget(uint32_t madeAt) {
    last_.reset();
    madeAt_ = madeAt;
  }
  /// \brief The frame the figures come from, if any.
  std::optional<uint32_t> lastTimed() const { return last_; }
  double pass1Ms() const { return pass1Ms_; }
  double pyramidMs() const { return pyramidMs_; }
  double cullMs() const { return cullMs_; }
  double pass2Ms() const { return pass2Ms_; }
  /// \brief "timed frame 30 (4 frames ago), wall clock per pass, every 30 frames", or why
  /// there are no figures.
  std::string describe(uint32_t frame) const;

 private:
  uint32_t interval_;
  std::optional<uint32_t> last_;
  std::optional<uint32_t> madeAt_;
  double pass1Ms_ = 0, pyramidMs_ = 0, cullMs_ = 0, pass2Ms_ = 0;
};

/// \brief The back-patch methods the `m` key cycles through.
const std::vector<std::string>& backPatchMethods();

/// \brief Applies one key (a printable character, or "space", "esc", "plus", "minus")
/// and returns a line saying what changed, or nullopt for a key without a binding.
/// Changes to the cull stages are reported so the caller rebuilds its cull frame.
std::optional<std::string> pressKey(ViewState& state, std::string_view key);

/// \brief The key bindings, one line each, for --help and the start of a run, with where
/// they differ from OpenSubdiv's glViewer and why.
std::string keyHelp();
/// \brief The same bindings in four short lines, for the HUD's keys section.
std::string keyHelpCompact();

/// \brief One step of a --script: press a key, drag the camera, wait for a frame, or keep
/// the image of the coming frame.
struct ScriptStep {
  enum class Kind { Key, Orbit, Pan, Zoom, WaitFrame, Shot } kind = Kind::Key;
  std::string key;     ///< Kind::Key
  double a = 0.0;      ///< Orbit: yaw degrees; Pan: right (bounding radii); Zoom: factor
  double b = 0.0;      ///< Orbit: pitch degrees; Pan: up (bounding radii)
  uint32_t frame = 0;  ///< WaitFrame: the frame the following steps apply before
};

/// \brief A bad `--script`: a usage error (osd-cull exits with status 2, as for any bad
/// command line), not a failure of the input files or the device.
class ScriptError : public Error {
 public:
  using Error::Error;
};

/// \brief Parses a script: whitespace-separated tokens, each a key name (as pressKey
/// takes), `orbit:YAW,PITCH` (degrees), `zoom:FACTOR`, `shot` (write the image of the coming
/// frame, see screenshotPath()) or `@N` (the following steps happen before frame N,
/// counting from 0; frames must not decrease).
/// \throws ScriptError naming the token and what is wrong with it.
std::vector<ScriptStep> parseScript(std::string_view text);

/// \brief Plays a parsed script frame by frame: steps up to the next `@N` with N greater
/// than the current frame are applied before that frame.
class ScriptPlayer {
 public:
  explicit ScriptPlayer(std::vector<ScriptStep> steps) : steps_(std::move(steps)) {}
  /// \brief Applies the steps due before `frame`; returns the lines pressKey returned.
  std::vector<std::string> beforeFrame(uint32_t frame, ViewState& state);
  bool done() const { return next_ >= steps_.size(); }
  /// \brief True once when a `shot` step came before the current frame.
  bool takeShot() { return std::exchange(shot_, false); }
  /// \brief True when the script has a `shot` step.
  bool hasShots() const;

 private:
  std::vector<ScriptStep> steps_;
  size_t next_ = 0;
  bool shot_ = false;
};

/// \brief Where a script's `shot` of frame `frame` goes: FILE.png becomes FILE-frameN.png.
std::string screenshotPath(const std::string& screenshot, uint32_t frame);

/// \brief Moves `state` to the next animation frame when it is playing, wrapping after
/// `frameCount` frames (the scene's length; 1 or 0: nothing moves).
void advanceAnimation(ViewState& state, uint32_t frameCount);

/// \brief Applies a camera drag (degrees) and zoom factor within the state's limits.
void orbitCamera(ViewState& state, double yawDegrees, double pitchDegrees);
void zoomCamera(ViewState& state, double factor);
/// \brief Pans the orbit pivot by (`right`, `up`) bounding radii within the state's limits.
void panCamera(ViewState& state, double right, double up);

}  // namespace osd_cull::viewer
