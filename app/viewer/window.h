#pragma once
// The GLFW window: creation, the Vulkan surface, and the input the viewer reads each frame
// (scroll and dropped files arrive through callbacks and are collected here).
#include <string>
#include <vector>

#include <volk.h>

struct GLFWwindow;

namespace rayster::app {

class Window {
 public:
  // Fails (returns an empty window) when no display is available; error() says why.
  Window(int width, int height, const char* title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  bool ok() const { return window_ != nullptr; }
  const std::string& error() const { return error_; }
  GLFWwindow* handle() const { return window_; }
  static std::vector<std::string> requiredInstanceExtensions();
  VkResult createSurface(VkInstance instance, VkSurfaceKHR* surface) const;

  bool shouldClose() const;
  void poll();
  void waitEvents();
  VkExtent2D framebufferSize() const;
  void setSize(int width, int height);
  void setTitle(const std::string& title);

  // Input gathered since the last takeScroll()/takeDrops().
  float takeScroll();
  std::vector<std::string> takeDrops();

 private:
  GLFWwindow* window_ = nullptr;
  std::string error_;
  float scroll_ = 0.0f;
  std::vector<std::string> drops_;
};

}  // namespace rayster::app
