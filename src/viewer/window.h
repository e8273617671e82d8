// Rank 0's window: a GLFW window with no client API (Vulkan presents to it), or, headless, none at
// all (VK_EXT_headless_surface: no X server needed; input comes from --script only). Window input
// arrives as InputEvents in window pixels.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "viewer/input.h"
#include "vk/present/swapchain.h"

struct GLFWwindow;

namespace sm::view {

class Window {
 public:
  // Opens the window; throws sm::Error (one line) when there is no display to open it on.
  Window(int width, int height, const std::string& title, bool headless);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  bool headless() const { return window_ == nullptr; }
  // Instance extensions the surface needs (ContextOptions::instanceExtensions).
  std::vector<std::string> instanceExtensions() const;
  vk::Surface createSurface(const vk::Context& ctx) const;

  // Handles the window system's events; appends the input among them to `events`.
  void poll(std::vector<InputEvent>& events);
  // Sleeps until an event arrives or `seconds` pass (while minimised).
  void wait(double seconds);
  bool closeRequested() const;
  // Size of the drawable area in pixels (0 x 0 while minimised).
  std::pair<int, int> framebufferSize() const;
  void requestSize(int width, int height);
  void setTitle(const std::string& title);

 private:
  static void onCursor(GLFWwindow* w, double x, double y);
  static void onButton(GLFWwindow* w, int button, int action, int mods);
  static void onScroll(GLFWwindow* w, double dx, double dy);
  static void onKey(GLFWwindow* w, int key, int scancode, int action, int mods);
  std::pair<double, double> toPixels(double x, double y) const;

  GLFWwindow* window_ = nullptr;
  int headlessWidth_ = 0, headlessHeight_ = 0;
  std::vector<InputEvent> queued_;
};

}  // namespace sm::view
