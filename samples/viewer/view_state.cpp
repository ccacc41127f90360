#include "view_state.h"

#include "osd_cull/error.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace osd_cull::viewer {
namespace {

std::string onOff(bool on) { return on ? "on" : "off"; }

double parseNumber(const std::string& text, const std::string& token) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v))
    throw ScriptError("--script: '" + token + "': '" + text + "' is not a finite number");
  return v;
}

}  // namespace

std::string ViewState::cullLabel() const {
  if (plan) return "plan";
  std::string s;
  auto add = [&](const std::string& part) { s += (s.empty() ? "" : "+") + part; };
  if (frustum) add("frustum");
  if (backPatch) add("backpatch(" + backPatchMethod + ")");
  if (occlusion) add("hiz");
  return s.empty() ? "none" : s;
}

const std::vector<std::string>& backPatchMethods() {
  static const std::vector<std::string> methods = {"tcone", "ncone", "tangent-plane"};
  return methods;
}

std::optional<std::string> pressKey(ViewState& s, std::string_view key) {
  if (key == "plus" || key == "+" || key == "=") {
    if (s.adaptive) {
      s.pixelsPerSegment = std::max(1.0, s.pixelsPerSegment / 1.5);
      return "adaptive: " + std::to_string(s.pixelsPerSegment) + " pixels per segment";
    }
    s.tessLevel = std::min(s.maxTessLevel, s.tessLevel + 1);
    return "tessellation " + std::to_string(s.tessLevel);
  }
  if (key == "minus" || key == "-") {
    if (s.adaptive) {
      s.pixelsPerSegment = std::min(256.0, s.pixelsPerSegment * 1.5);
      return "adaptive: " + std::to_string(s.pixelsPerSegment) + " pixels per segment";
    }
    s.tessLevel = std::max(1u, s.tessLevel - 1);
    return "tessellation " + std::to_string(s.tessLevel);
  }
  if (key == "a") return "adaptive tessellation " + onOff(s.adaptive = !s.adaptive);
  if (key == "p") return "effect plan " + onOff(s.plan = !s.plan);
  // A stage key takes manual control from the plan, said so.
  const std::string manual =
      (key == "1" || key == "2" || key == "3" || key == "c") && std::exchange(s.plan, false)
          ? " (plan off: stages by hand)"
          : "";
  if (key == "1") return "frustum culling " + onOff(s.frustum = !s.frustum) + manual;
  if (key == "2") return "back-patch culling " + onOff(s.backPatch = !s.backPatch) + manual;
  if (key == "3") return "occlusion culling " + onOff(s.occlusion = !s.occlusion) + manual;
  if (key == "c") {
    const bool on = !s.anyCull();
    s.frustum = s.backPatch = s.occlusion = on;
    return "culling " + s.cullLabel() + manual;
  }
  if (key == "m") {
    const auto& all = backPatchMethods();
    auto it = std::find(all.begin(), all.end(), s.backPatchMethod);
    s.backPatchMethod = (it == all.end() || it + 1 == all.end()) ? all.front() : *(it + 1);
    return "back-patch method " + s.backPatchMethod;
  }
  if (key == "s") return "status colors " + onOff(s.statusColors = !s.statusColors);
  if (key == "t") return "patch-type colors " + onOff(s.typeColors = !s.typeColors);
  if (key == "w") return "wireframe " + onOff(s.wireframe = !s.wireframe);
  if (key == "space")
    return "animation " + std::string((s.playing = !s.playing) ? "playing" : "paused");
  if (key == "r") return "turntable " + onOff(s.turntable = !s.turntable);
  if (key == "v")
    return "camera " + std::string((s.sceneCamera = !s.sceneCamera) ? "of the scene" : "orbit");
  if (key == "z")
    return "cull camera " +
           std::string((s.freezeCull = !s.freezeCull) ? "frozen" : "follows the view");
  if (key == "h") return "HUD " + onOff(s.showHud = !s.showHud);
  if (key == "f") {
    s.yawDegrees = s.pitchDegrees = s.panX = s.panY = 0.0;
    s.zoom = 1.0;
    return "camera reset";
  }
  if (key == "q" || key == "esc") {
    s.quit = true;
    return "quit";
  }
  return std::nullopt;
}

std::string keyHelp() {
  return "  + / -    tessellation level up / down (adaptive: finer / coarser)\n"
         "  a        adaptive tessellation on/off\n"
         "  p        the effect plan chooses the cull stages (default when calibrated)\n"
         "  1 2 3    frustum / back-patch / occlusion culling on/off (takes over from the plan)\n"
         "  c        all culling on/off\n"
         "  m        next back-patch method (tcone, ncone, tangent-plane)\n"
         "  s        status colors (visible, newly visible, culled by frustum / back-patch / "
         "occlusion)\n"
         "  t        patch-type colors (regular, boundary, corner, Gregory)\n"
         "  w        wireframe\n"
         "  space    animation play/pause (deforming meshes, moving instances, camera paths)\n"
         "  r        turntable (the orbit camera turns) on/off\n"
         "  v        look through the scene's camera (and its path) / the orbit camera\n"
         "  z        freeze the cull camera and fly around what it culled\n"
         "  f        reset the camera;  h  HUD on/off;  q / Esc  quit (as glViewer)\n"
         "  mouse    left drag: orbit, middle drag: pan (as glViewer), right drag or wheel:\n"
         "           zoom\n"
         "Unlike OpenSubdiv's glViewer: its number keys set the refinement level; here 1 2 3\n"
         "switch the cull stages, the stages being what this viewer is about, and + / -\n"
         "set the tessellation level (the patches are refined once, adaptively, at load).\n";
}

std::string keyHelpCompact() {
  return "+/- tess  a adaptive  p plan  1 2 3 stages  c all  m method\n"
         "s status colors  t type colors  w wireframe  space play\n"
         "r turntable  v scene camera  z freeze cull  f reset  h HUD\n"
         "q/Esc quit  drag: orbit  middle: pan  right/wheel: zoom\n";
}

std::vector<ScriptStep> parseScript(std::string_view text) {
  std::vector<ScriptStep> steps;
  std::istringstream in{std::string(text)};
  std::string token;
  uint32_t lastFrame = 0;
  ViewState probe;
  while (in >> token) {
    ScriptStep step;
    if (token[0] == '@') {
      const double f = parseNumber(token.substr(1), token);
      if (f < 0 || f > 1e7 || f != std::floor(f))
        throw ScriptError("--script: '" + token + "': a frame number must be a whole number >= 0");
      step.kind = ScriptStep::Kind::WaitFrame;
      step.frame = static_cast<uint32_t>(f);
      if (step.frame < lastFrame)
        throw ScriptError("--script: '" + token + "' comes after @" + std::to_string(lastFrame) +
                          ": frames must not decrease");
      lastFrame = step.frame;
    } else if (token.starts_with("orbit:") || token.starts_with("pan:")) {
      const bool orbit = token.starts_with("orbit:");
      const std::string args = token.substr(orbit ? 6 : 4);
      const size_t comma = args.find(',');
      if (comma == std::string::npos)
        throw ScriptError("--script: '" + token + "': expected " +
                          (orbit ? "orbit:YAW,PITCH" : "pan:RIGHT,UP"));
      step.kind = orbit ? ScriptStep::Kind::Orbit : ScriptStep::Kind::Pan;
      step.a = parseNumber(args.substr(0, comma), token);
      step.b = parseNumber(args.substr(comma + 1), token);
    } else if (token == "shot") {
      step.kind = ScriptStep::Kind::Shot;
    } else if (token.starts_with("zoom:")) {
      step.kind = ScriptStep::Kind::Zoom;
      step.a = parseNumber(token.substr(5), token);
      if (!(step.a > 0.0))
        throw ScriptError("--script: '" + token + "': the zoom factor must be > 0");
    } else {
      ViewState scratch = probe;
      if (!pressKey(scratch, token))
        throw ScriptError("--script: '" + token +
                          "' is not a key, orbit:YAW,PITCH, pan:RIGHT,UP, zoom:F, shot or "
                          "@FRAME "
                          "(`osd-cull view --help` lists the keys)");
      step.key = token;
    }
    steps.push_back(std::move(step));
  }
  return steps;
}

std::vector<std::string> ScriptPlayer::beforeFrame(uint32_t frame, ViewState& state) {
  std::vector<std::string> lines;
  while (next_ < steps_.size()) {
    const ScriptStep& step = steps_[next_];
    if (step.kind == ScriptStep::Kind::WaitFrame) {
      if (step.frame > frame) break;
    } else if (step.kind == ScriptStep::Kind::Orbit) {
      orbitCamera(state, step.a, step.b);
      lines.push_back("orbit " + std::to_string(step.a) + ", " + std::to_string(step.b));
    } else if (step.kind == ScriptStep::Kind::Pan) {
      panCamera(state, step.a, step.b);
      lines.push_back("pan " + std::to_string(state.panX) + ", " + std::to_string(state.panY));
    } else if (step.kind == ScriptStep::Kind::Zoom) {
      zoomCamera(state, step.a);
      lines.push_back("zoom " + std::to_string(state.zoom));
    } else if (step.kind == ScriptStep::Kind::Shot) {
      shot_ = true;
      lines.push_back("screenshot of frame " + std::to_string(frame));
    } else if (auto line = pressKey(state, step.key)) {
      lines.push_back(*line);
    }
    ++next_;
  }
  return lines;
}

bool ScriptPlayer::hasShots() const {
  return std::any_of(steps_.begin(), steps_.end(),
                     [](const ScriptStep& s) { return s.kind == ScriptStep::Kind::Shot; });
}

std::string screenshotPath(const std::string& screenshot, uint32_t frame) {
  const std::string suffix = "-frame" + std::to_string(frame);
  const size_t dot = screenshot.rfind('.');
  const size_t slash = screenshot.find_last_of("/\\");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return screenshot + suffix;
  return screenshot.substr(0, dot) + suffix + screenshot.substr(dot);
}

bool PassTiming::due(uint32_t frame) const {
  if (interval_ == 0) return false;
  return last_ ? frame >= *last_ + interval_ : !madeAt_ || frame != *madeAt_;
}

void PassTiming::record(uint32_t frame, double pass1Ms, double pyramidMs, double cullMs,
                        double pass2Ms) {
  last_ = frame;
  pass1Ms_ = pass1Ms;
  pyramidMs_ = pyramidMs;
  cullMs_ = cullMs;
  pass2Ms_ = pass2Ms;
}

std::string PassTiming::describe(uint32_t frame) const {
  if (interval_ == 0) return "per-pass timing off (--time-passes 0)";
  if (!last_) return "no timed frame yet";
  const uint32_t age = frame - *last_;
  return "timed frame " + std::to_string(*last_) + " (" + std::to_string(age) +
         (age == 1 ? " frame" : " frames") +
         " ago; wall clock of each pass submitted alone, every " + std::to_string(interval_) +
         " frames)";
}

void advanceAnimation(ViewState& state, uint32_t frameCount) {
  if (!state.playing || frameCount < 2) return;
  state.sceneFrame = (state.sceneFrame + 1) % frameCount;
}

void orbitCamera(ViewState& state, double yawDegrees, double pitchDegrees) {
  state.yawDegrees = std::fmod(state.yawDegrees + yawDegrees, 360.0);
  state.pitchDegrees = std::clamp(state.pitchDegrees + pitchDegrees, -85.0, 85.0);
}

void panCamera(ViewState& state, double right, double up) {
  if (!std::isfinite(right) || !std::isfinite(up)) return;
  state.panX = std::clamp(state.panX + right, -4.0, 4.0);
  state.panY = std::clamp(state.panY + up, -4.0, 4.0);
}

void zoomCamera(ViewState& state, double factor) {
  if (!(factor > 0.0) || !std::isfinite(factor)) return;
  state.zoom = std::clamp(state.zoom * factor, 0.05, 20.0);
}

}  // namespace osd_cull::viewer
