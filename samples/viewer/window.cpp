#include "window.h"

#include "osd_cull/error.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <cstdlib>

namespace osd_cull::viewer {
namespace {

std::string glfwProblem() {
  const char* text = nullptr;
  const int code = glfwGetError(&text);
  return code == GLFW_NO_ERROR ? std::string("unknown GLFW error")
                               : std::string(text ? text : "GLFW error");
}

}  // namespace

Window::Window(uint32_t width, uint32_t height, const std::string& title) {
  if (!glfwInit()) {
    const char* display = std::getenv("DISPLAY");
    throw Error("cannot open a window (" + glfwProblem() + ")" +
                (display && *display
                     ? std::string("")
                     : std::string("; DISPLAY is not set: run under `xvfb-run -a`")));
  }
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    throw Error("GLFW finds no Vulkan loader; install libvulkan1");
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(static_cast<int>(width), static_cast<int>(height), title.c_str(),
                             nullptr, nullptr);
  if (!window_) {
    const std::string problem = glfwProblem();
    glfwTerminate();
    throw Error("cannot create a " + std::to_string(width) + "x" + std::to_string(height) +
                " window: " + problem);
  }
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, onKey);
  glfwSetCharCallback(window_, onChar);
  glfwSetCursorPosCallback(window_, onCursor);
  glfwSetScrollCallback(window_, onScroll);
}

Window::~Window() {
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

std::vector<std::string> Window::requiredInstanceExtensions() {
  uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  if (!names) throw Error("GLFW cannot present with Vulkan here: " + glfwProblem());
  return std::vector<std::string>(names, names + count);
}

VkSurfaceKHR Window::createSurface(VkInstance instance) const {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  const VkResult r = glfwCreateWindowSurface(instance, window_, nullptr, &surface);
  if (r != VK_SUCCESS)
    throw Error("glfwCreateWindowSurface failed (VkResult " + std::to_string(r) +
                "): " + glfwProblem());
  return surface;
}

bool Window::poll() {
  glfwPollEvents();
  return !glfwWindowShouldClose(window_);
}

void Window::framebufferSize(uint32_t& width, uint32_t& height) const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  width = static_cast<uint32_t>(w > 0 ? w : 0);
  height = static_cast<uint32_t>(h > 0 ? h : 0);
}

WindowInput Window::takeInput() {
  WindowInput out = std::move(input_);
  input_ = {};
  return out;
}

void Window::onKey(GLFWwindow* w, int key, int, int action, int) {
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  if (self->uiKeyboard_) return;
  // Printable keys arrive through onChar (layout-aware); here only the named ones.
  if (key == GLFW_KEY_ESCAPE) self->input_.keys.push_back("esc");
  if (key == GLFW_KEY_SPACE) self->input_.keys.push_back("space");
  if (key == GLFW_KEY_KP_ADD) self->input_.keys.push_back("plus");
  if (key == GLFW_KEY_KP_SUBTRACT) self->input_.keys.push_back("minus");
}

void Window::onChar(GLFWwindow* w, unsigned int codepoint) {
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
  if (self->uiKeyboard_ || codepoint == ' ' || codepoint >= 128) return;
  self->input_.keys.emplace_back(1, static_cast<char>(codepoint));
}

void Window::onCursor(GLFWwindow* w, double x, double y) {
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
  const double dx = self->haveCursor_ ? x - self->lastX_ : 0.0;
  const double dy = self->haveCursor_ ? y - self->lastY_ : 0.0;
  self->lastX_ = x;
  self->lastY_ = y;
  self->haveCursor_ = true;
  if (self->uiMouse_) return;
  if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) {
    self->input_.orbitX += dx;
    self->input_.orbitY += dy;
  } else if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) {
    self->input_.zoomY += dy;
  } else if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS) {
    self->input_.panX += dx;
    self->input_.panY += dy;
  }
}

void Window::onScroll(GLFWwindow* w, double, double dy) {
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
  if (!self->uiMouse_) self->input_.wheel += dy;
}

}  // namespace osd_cull::viewer
