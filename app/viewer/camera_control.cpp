#include "app/viewer/camera_control.h"

#include <algorithm>
#include <cmath>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace rayster::app {
namespace {

constexpr float kTurnRadiansPerPixel = 0.005f;
constexpr float kWheelDollyFactor = 0.9f;  // per wheel notch, orbit distance
constexpr float kWheelSpeedFactor = 1.2f;  // per wheel notch, fly speed

// Turns `dir` by yaw about world up and by pitch about the camera's right, short of the poles.
glm::vec3 turn(glm::vec3 dir, glm::vec3 up, float yaw, float pitch) {
  const float len = glm::length(dir);
  glm::vec3 d = dir / len;
  const float cy = std::cos(yaw), sy = std::sin(yaw);
  d = d * cy + glm::cross(up, d) * sy + up * glm::dot(up, d) * (1.0f - cy);
  const float elevation = std::asin(std::clamp(glm::dot(d, up), -1.0f, 1.0f));
  const float target = std::clamp(elevation + pitch, -1.5f, 1.5f);
  const glm::vec3 flat = glm::normalize(d - up * glm::dot(d, up));
  return (flat * std::cos(target) + up * std::sin(target)) * len;
}

}  // namespace

void CameraControl::reset(const scene::Camera& camera) {
  camera_ = camera;
  flySpeed = std::max(0.1f, glm::length(camera.target - camera.position));
}

void CameraControl::frame(const scene::Aabb& bounds) {
  if (!bounds.valid()) return;
  const glm::vec3 centre = bounds.centre();
  const float radius = 0.5f * glm::length(bounds.max - bounds.min);
  glm::vec3 dir = glm::normalize(camera_.target - camera_.position);
  const float distance = radius / std::sin(0.5f * camera_.yFov) * 1.05f;
  camera_.target = centre;
  camera_.position = centre - dir * distance;
  camera_.zFar = std::max(camera_.zFar, distance + 2.0f * radius);
  flySpeed = std::max(0.1f, radius);
}

bool CameraControl::update(GLFWwindow* window, float dt, float scroll, bool mouseFree, bool keysFree) {
  bool moved = false;
  glm::dvec2 cursor;
  glfwGetCursorPos(window, &cursor.x, &cursor.y);
  const glm::vec2 delta = dragging_ ? glm::vec2(cursor - lastCursor_) : glm::vec2(0.0f);
  lastCursor_ = cursor;
  const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  const bool right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  const bool middle = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
  dragging_ = mouseFree && (left || right || middle);

  glm::vec3 forward = camera_.target - camera_.position;
  const float distance = glm::length(forward);
  const glm::vec3 up = glm::normalize(camera_.up);
  const glm::vec3 right3 = glm::normalize(glm::cross(forward, up));
  const glm::vec3 camUp = glm::normalize(glm::cross(right3, forward));
  if (mode == CameraMode::Orbit) {
    if (left && delta != glm::vec2(0.0f)) {
      camera_.position =
          camera_.target - turn(forward, up, -delta.x * kTurnRadiansPerPixel, delta.y * kTurnRadiansPerPixel);
      moved = true;
    }
    if ((right || middle) && delta != glm::vec2(0.0f)) {
      const float perPixel = 2.0f * distance * std::tan(0.5f * camera_.yFov) / 720.0f;
      const glm::vec3 pan = (-delta.x * right3 + delta.y * camUp) * perPixel;
      camera_.position += pan;
      camera_.target += pan;
      moved = true;
    }
    if (scroll != 0.0f) {
      camera_.position = camera_.target - forward * std::pow(kWheelDollyFactor, scroll);
      moved = true;
    }
  } else {
    if ((right || left) && delta != glm::vec2(0.0f)) {
      camera_.target =
          camera_.position + turn(forward, up, -delta.x * kTurnRadiansPerPixel, -delta.y * kTurnRadiansPerPixel);
      moved = true;
    }
    if (scroll != 0.0f) flySpeed *= std::pow(kWheelSpeedFactor, scroll);
    if (keysFree) {
      glm::vec3 move(0.0f);
      const glm::vec3 f = forward / distance;
      auto key = [&](int k) { return glfwGetKey(window, k) == GLFW_PRESS ? 1.0f : 0.0f; };
      move += f * (key(GLFW_KEY_W) - key(GLFW_KEY_S));
      move += right3 * (key(GLFW_KEY_D) - key(GLFW_KEY_A));
      move += up * (key(GLFW_KEY_E) - key(GLFW_KEY_Q));
      if (move != glm::vec3(0.0f)) {
        const glm::vec3 step = move * flySpeed * dt;
        camera_.position += step;
        camera_.target += step;
        moved = true;
      }
    }
  }
  return moved;
}

}  // namespace rayster::app
