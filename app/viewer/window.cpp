#include "app/viewer/window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cstdio>

namespace rayster::app {
namespace {

std::string gLastGlfwError;

void onError(int, const char* description) { gLastGlfwError = description; }

Window* self(GLFWwindow* w) { return static_cast<Window*>(glfwGetWindowUserPointer(w)); }

}  // namespace

Window::Window(int width, int height, const char* title) {
  glfwSetErrorCallback(onError);
  if (!glfwInit()) {
    error_ = "cannot open a window (" + (gLastGlfwError.empty() ? std::string("no display") : gLastGlfwError) +
             "); set DISPLAY or run under xvfb-run";
    return;
  }
  if (!glfwVulkanSupported()) {
    error_ = "GLFW found no Vulkan loader";
    return;
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(width, height, title, nullptr, nullptr);
  if (!window_) {
    error_ = "cannot create a window: " + gLastGlfwError;
    return;
  }
  glfwSetWindowUserPointer(window_, this);
  // Installed before ImGui's backend, which chains to them after taking what it needs.
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
    if (!ImGui::GetCurrentContext() || !ImGui::GetIO().WantCaptureMouse) self(w)->scroll_ += float(dy);
  });
  glfwSetDropCallback(window_, [](GLFWwindow* w, int count, const char** paths) {
    for (int i = 0; i < count; ++i) self(w)->drops_.emplace_back(paths[i]);
  });
}

Window::~Window() {
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

std::vector<std::string> Window::requiredInstanceExtensions() {
  uint32_t n = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&n);
  return std::vector<std::string>(names, names + n);
}

// GLFW's own Vulkan loader finds the same libvulkan as volk; only the surface call crosses over
// (glfw3.h declares it because volk.h brought the Vulkan types in first).
VkResult Window::createSurface(VkInstance instance, VkSurfaceKHR* surface) const {
  VkResult r = glfwCreateWindowSurface(instance, window_, nullptr, surface);
  return r;
}

bool Window::shouldClose() const { return glfwWindowShouldClose(window_); }
void Window::poll() { glfwPollEvents(); }
void Window::waitEvents() { glfwWaitEventsTimeout(0.1); }

VkExtent2D Window::framebufferSize() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return {uint32_t(w), uint32_t(h)};
}

void Window::setSize(int width, int height) { glfwSetWindowSize(window_, width, height); }
void Window::setTitle(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

float Window::takeScroll() {
  float s = scroll_;
  scroll_ = 0.0f;
  return s;
}

std::vector<std::string> Window::takeDrops() { return std::move(drops_); }

}  // namespace rayster::app
