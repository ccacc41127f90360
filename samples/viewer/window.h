#pragma once
/// \file window.h
/// \brief A GLFW window for Vulkan (no client API) and the input it received: key names
/// as view_state.h takes them, mouse drags and wheel turns. Needs an X11 display
/// (`xvfb-run -a` without one).

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

struct GLFWwindow;

namespace osd_cull::viewer {

/// \brief Input gathered since the last call of Window::takeInput().
struct WindowInput {
  std::vector<std::string> keys;      ///< "a", "plus", "space", "esc", ...
  double orbitX = 0.0, orbitY = 0.0;  ///< left-button drag, pixels
  double zoomY = 0.0;                 ///< right-button drag, pixels
  double panX = 0.0, panY = 0.0;      ///< middle-button drag, pixels
  double wheel = 0.0;                 ///< wheel steps
};

class Window {
 public:
  /// \throws osd_cull::Error when GLFW cannot start (no display: the message says to run
  /// under xvfb-run) or the window cannot be made.
  Window(uint32_t width, uint32_t height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  /// \brief The instance extensions GLFW needs for a surface (VK_KHR_surface and the
  /// platform's). Call after construction.
  static std::vector<std::string> requiredInstanceExtensions();
  /// \brief A surface for this window; the caller destroys it before the instance.
  VkSurfaceKHR createSurface(VkInstance instance) const;

  GLFWwindow* handle() const { return window_; }
  /// \brief Processes window events; false once the window was asked to close.
  bool poll();
  /// \brief The framebuffer size in pixels (0 x 0 while minimised).
  void framebufferSize(uint32_t& width, uint32_t& height) const;
  WindowInput takeInput();
  /// \brief True while the HUD wants the mouse or keyboard (set by the HUD each frame).
  void setUiCapture(bool mouse, bool keyboard) {
    uiMouse_ = mouse;
    uiKeyboard_ = keyboard;
  }

 private:
  static void onKey(GLFWwindow* w, int key, int scancode, int action, int mods);
  static void onChar(GLFWwindow* w, unsigned int codepoint);
  static void onCursor(GLFWwindow* w, double x, double y);
  static void onScroll(GLFWwindow* w, double dx, double dy);

  GLFWwindow* window_ = nullptr;
  WindowInput input_;
  double lastX_ = 0.0, lastY_ = 0.0;
  bool haveCursor_ = false;
  bool uiMouse_ = false, uiKeyboard_ = false;
};

}  // namespace osd_cull::viewer
