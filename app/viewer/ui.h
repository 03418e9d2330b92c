#pragma once
// Dear ImGui (Debian's imgui with its GLFW and Vulkan backends) and the viewer's panel: render
// settings, camera, lights, per-pass GPU timings, frame time, rays per frame, device memory.
#include <deque>
#include <string>
#include <vector>

#include <volk.h>

#include "app/viewer/camera_control.h"
#include "app/viewer/selection.h"
#include "render/renderer.h"

struct GLFWwindow;
struct ImDrawData;

namespace rayster::rhi {
class Context;
}

namespace rayster::app {

// Everything the panel shows and edits; the viewer acts on the flags it sets.
struct PanelState {
  render::RenderSettings settings;  // edits restart the run (histories reset)
  bool vsync = true;
  bool playPath = false;       // follow the scene's camera path
  int namedCamera = -1;        // set when a named camera is picked: the viewer jumps to it
  bool frameScene = false;     // "frame the scene" pressed
  bool screenshot = false;     // "screenshot" pressed
  bool lightsChanged = false;  // a light of the scene was edited in place
  int debugView = 0;           // 0: the final image; i: render::aovNames()[i - 1], read back each frame
  Selection selection;         // the picked instance (click in the viewport)
  std::string message;         // errors and notices, shown in red at the top
  // Statistics of the last frames.
  std::vector<std::pair<std::string, double>> passes;
  std::deque<float> gpuHistory, cpuHistory;  // ms, rolling
  uint64_t raysPerFrame = 0, deviceBytes = 0;
  render::Primary primaryUsed = render::Primary::Raster;
};

class Ui {
 public:
  Ui(rhi::Context& ctx, GLFWwindow* window, VkRenderPass pass, uint32_t minImages, uint32_t images);
  ~Ui();
  Ui(const Ui&) = delete;
  Ui& operator=(const Ui&) = delete;

  // Builds the panel; returns true when a render setting changed.
  bool build(PanelState& state, CameraControl& camera, scene::Scene& scene, const std::string& device);
  ImDrawData* draw();  // finishes the frame's UI
  // A frame of its own showing only `message` across the window (device loss, memory exhaustion);
  // closes the panel's frame first if one is open.
  ImDrawData* drawMessage(const std::string& message);
  bool wantsMouse() const;
  bool wantsKeyboard() const;

 private:
  rhi::Context& ctx_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  bool frameOpen_ = false;  // between build() and draw()
};

}  // namespace rayster::app
