#pragma once
// Interactive camera: orbit (drag to turn around a pivot, right-drag to pan, wheel to dolly) and
// fly (right-drag to look, WASD to move, Q/E down/up, wheel to change speed).
#include <glm/glm.hpp>

#include "scene/scene.h"

struct GLFWwindow;

namespace rayster::app {

enum class CameraMode { Orbit, Fly };

class CameraControl {
 public:
  void reset(const scene::Camera& camera);  // take a camera (a named one, or the path's)
  void frame(const scene::Aabb& bounds);    // look at the whole scene from the current direction
  // Applies this frame's input; `mouseFree` is false while the UI has the mouse, `keysFree` the same
  // for the keyboard. Returns true when the camera moved.
  bool update(GLFWwindow* window, float dt, float scroll, bool mouseFree, bool keysFree);

  const scene::Camera& camera() const { return camera_; }
  CameraMode mode = CameraMode::Orbit;
  float flySpeed = 1.0f;  // scene units per second; the wheel scales it in fly mode

 private:
  scene::Camera camera_;
  glm::dvec2 lastCursor_{0.0};
  bool dragging_ = false;
};

}  // namespace rayster::app
