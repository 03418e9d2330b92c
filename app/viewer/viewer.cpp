// The `rayster view` loop: input → panel → one renderer frame → present. The renderer is the same
// one `rayster render` drives (Renderer::beginRun/renderFrame); the window is just another consumer
// of its output image.
#include "app/viewer/viewer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "app/device_option.h"
#include "app/render_command.h"
#include "app/viewer/camera_control.h"
#include "app/viewer/presenter.h"
#include "app/viewer/selection.h"
#include "app/viewer/shader_reload.h"
#include "app/viewer/ui.h"
#include "app/viewer/window.h"
#include "core/image_io.h"
#include "core/log.h"
#include "rhi/context.h"
#include "rhi/vk_check.h"
#include "scene/loader.h"

namespace rayster::app {

void recordHistory(std::deque<float>& history, float value);

namespace {

int fail(const Error& e) {
  std::fprintf(stderr, "rayster: error: %s\n", e.message.c_str());
  return int(e.code);
}

// Keys act on their press, not while held.
struct KeyEdges {
  bool down[GLFW_KEY_LAST + 1] = {};
  bool pressed(GLFWwindow* w, int key) {
    const bool now = glfwGetKey(w, key) == GLFW_PRESS;
    const bool edge = now && !down[key];
    down[key] = now;
    return edge;
  }
};

// Rays launched this frame: what the frame's passes declared (graph::PassInfo::rays; twins excluded).
uint64_t frameRays(const render::FrameStats& stats) {
  uint64_t rays = 0;
  for (const auto& p : stats.passes)
    if (p.info.kind == graph::PassKind::Frame) rays += p.info.rays;
  return rays;
}

// Device loss and memory exhaustion end the process (rhi/vk_check.h); the window says why first,
// in its title and drawn inside it, for kFatalSeconds. After a device loss drawing may fail: a
// Vulkan error inside the hook exits at once with the same documented code (the title stays).
constexpr double kFatalSeconds = 3.0;  // long enough to read one line
std::function<void(const char*)> gShowFatal;
void showFatal(const char* message) {
  if (gShowFatal) gShowFatal(message);
}

// Tests only: RAYSTER_VIEWER_FAIL_AT=oom:F or lost:F fails as that Vulkan error at frame F.
std::optional<std::pair<VkResult, uint32_t>> injectedFailure() {
  const char* v = std::getenv("RAYSTER_VIEWER_FAIL_AT");
  unsigned frame = 0;
  char kind[8] = {};
  if (!v || std::sscanf(v, "%7[a-z]:%u", kind, &frame) != 2) return std::nullopt;
  return std::pair{std::string(kind) == "lost" ? VK_ERROR_DEVICE_LOST : VK_ERROR_OUT_OF_DEVICE_MEMORY, frame};
}

// A click selects: a left press and release that did not drag (dragging turns the camera).
struct MousePick {
  static constexpr float kClickPixels = 3.0f;
  bool down = false, armed = false;
  glm::vec2 last{0.0f}, delta{0.0f};
  float travelled = 0.0f;
  // Returns the cursor position of a click that ended this frame.
  std::optional<glm::vec2> update(GLFWwindow* w, bool mouseFree) {
    double x = 0, y = 0;
    glfwGetCursorPos(w, &x, &y);
    const glm::vec2 now(x, y);
    delta = now - last;
    last = now;
    const bool pressed = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    std::optional<glm::vec2> click;
    if (pressed && !down) armed = mouseFree, travelled = 0.0f;  // a press on the panel is the panel's
    if (down) travelled += glm::length(delta);
    if (!pressed && down && armed && mouseFree && travelled <= kClickPixels) click = now;
    down = pressed;
    return click;
  }
};

const scene::Camera& startCamera(const scene::Scene& scene, const std::string& name) {
  for (const auto& c : scene.cameras)
    if (c.name == name) return c;
  return scene.cameras.front();
}

// One `rayster view` session: the window's loop around one renderer, and what the loop keeps
// between frames. Each step of a frame is a member function, called in order by run().
class ViewerSession {
 public:
  ViewerSession(const ViewOptions& o, Window& window, rhi::Context& vk, std::unique_ptr<scene::Scene> scene,
                std::unique_ptr<render::Renderer> renderer)
      : o_(o),
        window_(window),
        w_(window.handle()),
        vk_(vk),
        scene_(std::move(scene)),
        renderer_(std::move(renderer)),
        presenter_(vk, window.framebufferSize(), o.vsync),
        ui_(vk, window.handle(), presenter_.uiPass(), presenter_.swapchain().minImageCount(),
            presenter_.swapchain().imageCount()),
        showUi_(!o.hideUi),
        last_(std::chrono::steady_clock::now()),
        failAt_(injectedFailure())
#if RAYSTER_SHADER_HOT_RELOAD
        ,
        shaderReloader_(RAYSTER_GLSLC, RAYSTER_SHADER_DIR)
#endif
  {
    st_.settings = o.settings;
    st_.vsync = o.vsync;
    st_.playPath = o.settings.cameraPath;
    const auto& aovs = render::aovNames();
    if (auto it = std::find(aovs.begin(), aovs.end(), o.debugView); it != aovs.end())
      st_.debugView = int(it - aovs.begin()) + 1;
    camera_.reset(startCamera(*scene_, o.settings.camera));
    gShowFatal = [this](const char* message) { showFatalInWindow(message); };
    rhi::setFatalHook(showFatal);
  }
  ~ViewerSession() {
    rhi::setFatalHook(nullptr);
    gShowFatal = nullptr;
  }
  ViewerSession(const ViewerSession&) = delete;
  ViewerSession& operator=(const ViewerSession&) = delete;

  // Input → panel → one renderer frame → present, until the window closes or the scripted frames
  // are done. Returns the exit code of a failure, nothing when the session ended normally.
  std::optional<int> run() {
    while (!window_.shouldClose()) {
      window_.poll();
      applyScriptedResizes();
      VkExtent2D size = window_.framebufferSize();
      if (size.width == 0 || size.height == 0) {  // minimised: render nothing until restored
        window_.waitEvents();
        continue;
      }
      size = followWindowSize(size);
      if (const std::optional<int> failed = loadDroppedFile()) return failed;
      pollShaderReload();
      const float dt = tick();
      if (ui_.build(st_, camera_, *scene_, vk_.info().name))
        restart_ = true;
      else if (renderer_)
        renderer_->updateSettings(st_.settings);  // the tonemapper and the like: no restart
      handleKeys();
      applyPanelRequests();
      const bool grabbing = updateSelection();
      const bool moved =
          camera_.update(w_, dt, window_.takeScroll(), !ui_.wantsMouse() && !grabbing, !ui_.wantsKeyboard());
      if (restart_ && !beginRun(size)) continue;
      const bool lastFrame = o_.frames && frame_ + 1 == o_.frames;
      const bool shoot = (lastFrame && !o_.screenshot.empty()) || st_.screenshot;
      recordStats(renderFrame(moved, shoot));
      Image8 captured;
      present(shoot ? &captured : nullptr);
      if (shoot)
        if (const std::optional<int> failed = writeScreenshot(captured, lastFrame)) return failed;
      ++frame_;
      if (lastFrame) break;
    }
    vk_.waitIdle();
    return std::nullopt;
  }

 private:
  // --resize-at F:WxH: the window changes size at frame F.
  void applyScriptedResizes() {
    for (const auto& r : o_.resizes)
      if (r.frame == frame_) window_.setSize(int(r.width), int(r.height));
  }

  // A new window size or vsync setting recreates the swapchain (and restarts the run); returns
  // the size frames render at.
  VkExtent2D followWindowSize(VkExtent2D size) {
    const VkExtent2D current = presenter_.swapchain().extent();
    if (size.width != current.width || size.height != current.height || st_.vsync != presenter_.swapchain().vsync()) {
      presenter_.resize(size, st_.vsync);
      size = presenter_.swapchain().extent();
      restart_ = true;
    }
    return size;
  }

  // Dropped files replace the scene (the first one that loads). Returns the exit code when the new
  // scene's renderer cannot be created.
  std::optional<int> loadDroppedFile() {
    for (const std::string& path : window_.takeDrops()) {
      auto next = scene::loadScene(path);
      if (!next) {
        st_.message = next.error().message;
        continue;
      }
      vk_.waitIdle();
      renderer_.reset();
      scene_ = std::make_unique<scene::Scene>(std::move(*next));
      auto r = render::Renderer::create(vk_, *scene_);
      if (!r) return fail(r.error());
      renderer_ = std::move(*r);
      camera_.reset(scene_->cameras.front());
      st_.selection = {};
      st_.message = "loaded " + std::filesystem::path(path).filename().string();
      restart_ = true;
      break;
    }
    return std::nullopt;
  }

  // Development builds: recompiled shaders rebuild the pipelines (a failed compile keeps the old).
  void pollShaderReload() {
#if RAYSTER_SHADER_HOT_RELOAD
    if (const ShaderReloadResult reload = shaderReloader_.poll(); !reload.error.empty()) {
      st_.message = reload.error;  // the old pipelines stay
      log::warn("shader reload: {}", reload.error);
    } else if (!reload.reloaded.empty()) {
      renderer_->reloadPipelines();
      st_.message = "reloaded " + std::to_string(reload.reloaded.size()) + " shader(s)";
      log::info("shader reload: {} shader(s) recompiled, pipelines rebuilt", reload.reloaded.size());
      restart_ = true;
    }
#endif
  }

  // Seconds since the previous frame, also recorded for the panel's CPU graph.
  float tick() {
    const auto now = std::chrono::steady_clock::now();
    const float dt = std::chrono::duration<float>(now - last_).count();
    last_ = now;
    recordHistory(st_.cpuHistory, dt * 1000.0f);
    return dt;
  }

  // The keys of the README's table that the panel does not take.
  void handleKeys() {
    if (ui_.wantsKeyboard()) return;
    if (keys_.pressed(w_, GLFW_KEY_TAB)) showUi_ = !showUi_;
    if (keys_.pressed(w_, GLFW_KEY_F)) st_.frameScene = true;
    if (keys_.pressed(w_, GLFW_KEY_F12)) st_.screenshot = true;
    if (keys_.pressed(w_, GLFW_KEY_P) && !scene_->cameraPath.empty()) st_.playPath = !st_.playPath, restart_ = true;
    if (keys_.pressed(w_, GLFW_KEY_C))
      camera_.mode = camera_.mode == CameraMode::Orbit ? CameraMode::Fly : CameraMode::Orbit;
    if (keys_.pressed(w_, GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(w_, GLFW_TRUE);
    for (int k = 0; k < 9; ++k)
      if (keys_.pressed(w_, GLFW_KEY_1 + k) && k < int(scene_->cameras.size())) st_.namedCamera = k;
  }

  // Edited lights, a picked named camera and "frame the scene" are cuts: histories restart.
  void applyPanelRequests() {
    if (st_.lightsChanged) {
      renderer_->refreshLights();
      cut_ = true;
    }
    if (st_.namedCamera >= 0) {
      camera_.reset(scene_->cameras[size_t(st_.namedCamera)]);
      st_.namedCamera = -1;
      cut_ = true;
    }
    if (st_.frameScene) {
      camera_.frame(scene_->bounds());
      st_.frameScene = false;
      cut_ = true;
    }
  }

  // A click selects the instance under the cursor; holding G moves the selection with the mouse
  // instead of the camera (returns whether it does). Edits go to the renderer's instance table.
  bool updateSelection() {
    const bool grabbing =
        st_.selection.instance >= 0 && !ui_.wantsKeyboard() && glfwGetKey(w_, GLFW_KEY_G) == GLFW_PRESS;
    if (const auto clicked = pick_.update(w_, !ui_.wantsMouse() && !grabbing)) {
      std::vector<glm::mat4> transforms(scene_->instances.size());
      for (size_t i = 0; i < transforms.size(); ++i) transforms[i] = renderer_->instanceTransform(uint32_t(i));
      int ww = 0, wh = 0;
      glfwGetWindowSize(w_, &ww, &wh);
      st_.selection.instance = pickInstance(*scene_, transforms, camera_.camera(), *clicked, glm::vec2(ww, wh));
      if (st_.selection.instance >= 0) st_.selection.trs = decompose(transforms[size_t(st_.selection.instance)]);
    }
    if (grabbing && pick_.delta != glm::vec2(0.0f)) {
      int ww = 0, wh = 0;
      glfwGetWindowSize(w_, &ww, &wh);
      st_.selection.trs.position += dragOffset(camera_.camera(), st_.selection.trs.position, pick_.delta, float(wh));
      st_.selection.edited = true;
    }
    if (st_.selection.edited && st_.selection.instance >= 0)
      renderer_->setInstanceTransform(uint32_t(st_.selection.instance), compose(st_.selection.trs));
    st_.selection.edited = false;
    return grabbing;
  }

  // (Re)starts the run with the panel's settings at this size; on failure shows why, falls back to
  // the hybrid mode without the camera path and returns false (the next iteration tries again).
  bool beginRun(VkExtent2D size) {
    st_.settings.width = size.width;
    st_.settings.height = size.height;
    st_.settings.cameraPath = st_.playPath;
    st_.settings.frames = UINT32_MAX;  // the run lasts until the next restart
    if (auto begun = renderer_->beginRun(st_.settings); !begun) {
      st_.message = begun.error().message;
      st_.settings.mode = render::Mode::Hybrid;  // fall back to what works
      st_.settings.cameraPath = st_.playPath = false;
      return false;
    }
    restart_ = false;
    return true;
  }

  // One renderer frame from the viewer's camera (or the camera path); `shoot`: read it back.
  render::FrameStats renderFrame(bool moved, bool shoot) {
    render::FrameControl control;
    if (!st_.playPath) control.camera = camera_.camera();
    control.cut = cut_;
    control.moving = moved;
    control.present = true;
    control.readback = shoot || st_.debugView != 0;
    cut_ = false;
    const render::FrameStats stats = renderer_->renderFrame(control);
    if (failAt_ && failAt_->second == frame_) VK_CHECK(failAt_->first);
    if (st_.playPath) camera_.reset(stats.camera);  // leaving the path continues from where it is
    return stats;
  }

  void recordStats(const render::FrameStats& stats) {
    st_.passes.clear();
    for (const auto& p : stats.passes) st_.passes.emplace_back(p.name, p.ms);
    recordHistory(st_.gpuHistory, float(stats.gpuMs));
    st_.raysPerFrame = frameRays(stats);
    st_.deviceBytes = renderer_->deviceBytesUsed();
  }

  // A debug view shows one stage, read back and mapped for display as `--aov` PNGs are.
  std::optional<Image8> debugImage() {
    if (st_.debugView == 0) return std::nullopt;
    render::RenderOutput images = renderer_->readbackImages();
    if (images.aovs.empty()) {
      st_.message = "this scene has no " + render::aovNames()[size_t(st_.debugView - 1)];
      return std::nullopt;
    }
    return encodeSrgb8(aovForDisplay(images.aovs.front().first, std::move(images.aovs.front().second)));
  }

  // The frame (or the debug view) with the panel over it; `captured` receives the presented pixels.
  void present(Image8* captured) {
    const std::optional<Image8> shown = debugImage();
    ImDrawData* drawData = ui_.draw();
    if (!presenter_.present(renderer_->outputImage(), showUi_ ? drawData : nullptr, captured,
                            shown ? &*shown : nullptr))
      restart_ = true;  // out of date: the next iteration resizes
  }

  // --screenshot after the last frame, or F12: the window as shown (.png; F12 also the linear
  // frame as .exr), or the HDR frame (.exr). Ends the run. Returns the exit code of a failed write.
  std::optional<int> writeScreenshot(const Image8& captured, bool lastFrame) {
    std::string path =
        lastFrame && !o_.screenshot.empty() ? o_.screenshot : "rayster-screenshot-" + std::to_string(frame_) + ".png";
    const bool exr = std::filesystem::path(path).extension() == ".exr";
    render::RenderOutput out = renderer_->endRun();
    restart_ = true;
    const ExrPixels pixels = o_.exrFloat ? ExrPixels::Float : ExrPixels::Half;
    Status written = exr ? writeExr(path, out.hdr, pixels) : writePng(path, captured);
    if (!written) return fail(written.error());
    // A screenshot key press writes both: the window as shown, and the linear frame.
    if (!exr && st_.screenshot)
      written = writeExr(std::filesystem::path(path).replace_extension(".exr"), out.hdr, pixels);
    st_.message = written ? "wrote " + path : written.error().message;
    log::info("wrote {} ({}x{}, frame {})", path, captured.width, captured.height, frame_ + 1);
    st_.screenshot = false;
    return std::nullopt;
  }

  // Device loss or memory exhaustion (rhi/vk_check.h): the cause in the title and drawn over a
  // black frame for kFatalSeconds, before the process exits.
  void showFatalInWindow(const char* message) {
    glfwSetWindowTitle(w_, (std::string("Rayster: error: ") + message + " (exiting)").c_str());
    Image8 black;
    const VkExtent2D e = presenter_.swapchain().extent();
    black.width = int(e.width);
    black.height = int(e.height);
    black.rgba.assign(size_t(e.width) * e.height * 4, 0);
    for (size_t i = 3; i < black.rgba.size(); i += 4) black.rgba[i] = 255;
    log::info("shown in the window: {}", message);
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(kFatalSeconds);
    while (std::chrono::steady_clock::now() < until) {
      glfwPollEvents();
      presenter_.present(renderer_->outputImage(), ui_.drawMessage(message), nullptr, &black);
      glfwWaitEventsTimeout(0.1);
    }
  }

  const ViewOptions& o_;
  Window& window_;
  GLFWwindow* w_;
  rhi::Context& vk_;
  std::unique_ptr<scene::Scene> scene_;
  std::unique_ptr<render::Renderer> renderer_;
  Presenter presenter_;
  Ui ui_;
  PanelState st_;
  MousePick pick_;
  CameraControl camera_;
  KeyEdges keys_;
  bool showUi_;
  bool restart_ = true, cut_ = false;  // restart: begin a new run; cut: the next frame drops history
  uint32_t frame_ = 0;
  std::chrono::steady_clock::time_point last_;
  std::optional<std::pair<VkResult, uint32_t>> failAt_;
#if RAYSTER_SHADER_HOT_RELOAD
  ShaderReloader shaderReloader_;
#endif
};

}  // namespace

int runViewer(const ViewOptions& o) {
  auto loaded = scene::loadScene(o.scene);
  if (!loaded) return fail(loaded.error());
  auto scene = std::make_unique<scene::Scene>(std::move(*loaded));
  Window window(int(o.width), int(o.height), "Rayster");
  if (!window.ok()) return fail(makeError(ExitCode::NoDevice, "{}", window.error()));
  rhi::ContextOptions co{o.validation,
                         true,
                         deviceSelector(o.device),
                         o.debugLabels,
                         Window::requiredInstanceExtensions(),
                         [&](VkInstance i, VkSurfaceKHR* s) { return window.createSurface(i, s); }};
  auto ctx = rhi::Context::create(co);
  if (!ctx) return fail(ctx.error());
  rhi::Context& vk = **ctx;
  {
    auto created = render::Renderer::create(vk, *scene);
    if (!created) return fail(created.error());
    ViewerSession session(o, window, vk, std::move(scene), std::move(*created));
    if (const std::optional<int> failed = session.run()) return *failed;
  }
  if (vk.validationEnabled() && vk.validationErrors() > 0) {
    std::fprintf(stderr, "rayster: error: %u Vulkan validation error(s)\n", vk.validationErrors());
    return int(ExitCode::Failure);
  }
  return 0;
}

}  // namespace rayster::app
