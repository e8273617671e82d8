#include "viewer/window.h"

#include <cstdlib>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "common/error.h"
#include "vk/vk_error.h"

namespace sm::view {
namespace {

std::string glfwMessage() {
  const char* what = nullptr;
  glfwGetError(&what);
  return what ? what : "unknown GLFW error";
}

bool hasDisplay() {
  const char* x = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (wayland && *wayland);
}

Window* owner(GLFWwindow* w) {
  return static_cast<Window*>(glfwGetWindowUserPointer(w));
}

Key keyOf(int key) {
  switch (key) {
    case GLFW_KEY_RIGHT:
      return Key::NextStep;
    case GLFW_KEY_LEFT:
      return Key::PrevStep;
    case GLFW_KEY_SPACE:
      return Key::TogglePlay;
    case GLFW_KEY_UP:
      return Key::MoreOpaque;
    case GLFW_KEY_DOWN:
      return Key::LessOpaque;
    case GLFW_KEY_F:
      return Key::NextField;
    case GLFW_KEY_C:
      return Key::NextColormap;
    case GLFW_KEY_LEFT_BRACKET:
      return Key::FinerStep;
    case GLFW_KEY_RIGHT_BRACKET:
      return Key::CoarserStep;
    case GLFW_KEY_R:
      return Key::ResetView;
    case GLFW_KEY_S:
      return Key::Screenshot;
    case GLFW_KEY_O:
      return Key::ToggleOverlay;
    case GLFW_KEY_L:
      return Key::ToggleLegend;
    case GLFW_KEY_H:
      return Key::Help;
    case GLFW_KEY_X:
      return Key::ToggleCut;
    case GLFW_KEY_COMMA:
      return Key::CutNearer;
    case GLFW_KEY_PERIOD:
      return Key::CutFarther;
    case GLFW_KEY_G:
      return Key::ToggleLogScale;
    case GLFW_KEY_P:
      return Key::ToggleProjection;
    case GLFW_KEY_Q:
    case GLFW_KEY_ESCAPE:
      return Key::Quit;
    default:
      return Key::None;
  }
}

}  // namespace

Window::Window(int width, int height, const std::string& title, bool headless) {
  if (headless) {
    headlessWidth_ = width;
    headlessHeight_ = height;
    return;
  }
  if (!hasDisplay())
    throw Error("view: no display (DISPLAY is not set): run under xvfb-run, or use --headless");
  if (!glfwInit()) throw Error("view: cannot open a window (", glfwMessage(), "); try --headless");
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    throw Error("view: GLFW finds no Vulkan loader to present with");
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    std::string why = glfwMessage();
    glfwTerminate();
    throw Error("view: cannot open a window (", why, ")");
  }
  glfwSetWindowUserPointer(window_, this);
  glfwSetCursorPosCallback(window_, &Window::onCursor);
  glfwSetMouseButtonCallback(window_, &Window::onButton);
  glfwSetScrollCallback(window_, &Window::onScroll);
  glfwSetKeyCallback(window_, &Window::onKey);
}

Window::~Window() {
  if (window_) {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
}

std::vector<std::string> Window::instanceExtensions() const {
  if (headless()) return vk::headlessSurfaceExtensions();
  uint32_t n = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&n);
  if (!names) throw Error("view: GLFW cannot present with Vulkan here (", glfwMessage(), ")");
  return std::vector<std::string>(names, names + n);
}

vk::Surface Window::createSurface(const vk::Context& ctx) const {
  if (headless()) return vk::Surface::headless(ctx);
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  VkResult r = glfwCreateWindowSurface(ctx.instance(), window_, nullptr, &surface);
  if (r != VK_SUCCESS)
    throw vk::VulkanError(std::string("glfwCreateWindowSurface: ") + vk::resultName(r), r);
  return vk::Surface(ctx, surface);
}

void Window::poll(std::vector<InputEvent>& events) {
  if (window_) glfwPollEvents();
  for (auto& e : queued_) events.push_back(std::move(e));
  queued_.clear();
}

void Window::wait(double seconds) {
  if (window_) glfwWaitEventsTimeout(seconds);
}

bool Window::closeRequested() const {
  return window_ && glfwWindowShouldClose(window_);
}

std::pair<int, int> Window::framebufferSize() const {
  if (!window_) return {headlessWidth_, headlessHeight_};
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return {w, h};
}

void Window::requestSize(int width, int height) {
  if (!window_) {
    headlessWidth_ = width;
    headlessHeight_ = height;
    return;
  }
  glfwSetWindowSize(window_, width, height);
}

void Window::setTitle(const std::string& title) {
  if (window_) glfwSetWindowTitle(window_, title.c_str());
}

// GLFW reports the cursor in screen coordinates; the image is in framebuffer pixels (they differ
// on high-DPI screens).
std::pair<double, double> Window::toPixels(double x, double y) const {
  int ww = 0, wh = 0, fw = 0, fh = 0;
  glfwGetWindowSize(window_, &ww, &wh);
  glfwGetFramebufferSize(window_, &fw, &fh);
  if (ww <= 0 || wh <= 0) return {x, y};
  return {x * fw / ww, y * fh / wh};
}

void Window::onCursor(GLFWwindow* w, double x, double y) {
  Window* self = owner(w);
  auto [px, py] = self->toPixels(x, y);
  self->queued_.push_back({InputEvent::Type::Move, px, py, Button::Left, Key::None, false, {}});
}

void Window::onButton(GLFWwindow* w, int button, int action, int mods) {
  Button b = button == GLFW_MOUSE_BUTTON_MIDDLE  ? Button::Middle
             : button == GLFW_MOUSE_BUTTON_RIGHT ? Button::Right
                                                 : Button::Left;
  if (button > GLFW_MOUSE_BUTTON_MIDDLE) return;
  auto type = action == GLFW_PRESS ? InputEvent::Type::Press : InputEvent::Type::Release;
  owner(w)->queued_.push_back({type, 0, 0, b, Key::None, bool(mods & GLFW_MOD_SHIFT), {}});
}

void Window::onScroll(GLFWwindow* w, double, double dy) {
  owner(w)->queued_.push_back(
      {InputEvent::Type::Scroll, 0, dy, Button::Left, Key::None, false, {}});
}

void Window::onKey(GLFWwindow* w, int key, int, int action, int mods) {
  if (action == GLFW_RELEASE) return;
  Key k = keyOf(key);
  if (k == Key::None || (action == GLFW_REPEAT && !keyRepeats(k))) return;
  owner(w)->queued_.push_back(
      {InputEvent::Type::KeyPress, 0, 0, Button::Left, k, bool(mods & GLFW_MOD_SHIFT), {}});
}

}  // namespace sm::view
