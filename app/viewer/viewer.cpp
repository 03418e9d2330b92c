// The `rayster view` loop: input → panel → one renderer frame → present. The renderer is the same
// one `rayster render` drives (Renderer::beginRun/renderFrame); the window is just another consumer
// of its output image.
#include "app/viewer/viewer.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

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
ImageF aovForDisplay(const std::string& name, ImageF img);  // render_command.cpp

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

} // namespace

int runViewer(const ViewOptions& o) {
  auto loaded = scene::loadScene(o.scene);
  if (!loaded) return fail(loaded.error());
  auto scene = std::make_unique<scene::Scene>(std::move(*loaded));
  Window window(int(o.width), int(o.height), "Rayster");
  if (!window.ok()) return fail(makeError(ExitCode::NoDevice, "{}", window.error()));
  rhi::ContextOptions co{o.validation, true, o.device, o.debugLabels, Window::requiredInstanceExtensions(),
                         [&](VkInstance i, VkSurfaceKHR* s) { return window.createSurface(i, s); }};
  auto ctx = rhi::Context::create(co);
  if (!ctx) return fail(ctx.error());
  rhi::Context& vk = **ctx;
  {
    auto created = render::Renderer::create(vk, *scene);
    if (!created) return fail(created.error());
    std::unique_ptr<render::Renderer> renderer = std::move(*created);
    Presenter presenter(vk, window.framebufferSize(), o.vsync);
    Ui ui(vk, window.handle(), presenter.uiPass(), presenter.swapchain().minImageCount(),
          presenter.swapchain().imageCount());
    PanelState st;
    st.settings = o.settings;
    st.vsync = o.vsync;
    st.playPath = o.settings.cameraPath;
    const auto& aovs = render::aovNames();
    if (auto it = std::find(aovs.begin(), aovs.end(), o.debugView); it != aovs.end())
      st.debugView = int(it - aovs.begin()) + 1;
    MousePick pick;
    CameraControl camera;
    camera.reset(startCamera(*scene, o.settings.camera));
    bool showUi = !o.hideUi, restart = true, cut = false;
    KeyEdges keys;
    uint32_t frame = 0;
    auto last = std::chrono::steady_clock::now();
    GLFWwindow* w = window.handle();
    gShowFatal = [&](const char* message) {
      glfwSetWindowTitle(w, (std::string("Rayster: error: ") + message + " (exiting)").c_str());
      Image8 black;
      const VkExtent2D e = presenter.swapchain().extent();
      black.width = int(e.width);
      black.height = int(e.height);
      black.rgba.assign(size_t(e.width) * e.height * 4, 0);
      for (size_t i = 3; i < black.rgba.size(); i += 4) black.rgba[i] = 255;
      log::info("shown in the window: {}", message);
      const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(kFatalSeconds);
      while (std::chrono::steady_clock::now() < until) {
        glfwPollEvents();
        presenter.present(renderer->outputImage(), ui.drawMessage(message), nullptr, &black);
        glfwWaitEventsTimeout(0.1);
      }
    };
    rhi::setFatalHook(showFatal);
    const auto failAt = injectedFailure();
#if RAYSTER_SHADER_HOT_RELOAD
    ShaderReloader shaderReloader(RAYSTER_GLSLC, RAYSTER_SHADER_DIR);
#endif

    while (!window.shouldClose()) {
      window.poll();
      for (const auto& r : o.resizes)
        if (r.frame == frame) window.setSize(int(r.width), int(r.height));
      VkExtent2D size = window.framebufferSize();
      if (size.width == 0 || size.height == 0) {  // minimised: render nothing until restored
        window.waitEvents();
        continue;
      }
      if (size.width != presenter.swapchain().extent().width || size.height != presenter.swapchain().extent().height ||
          st.vsync != presenter.swapchain().vsync()) {
        presenter.resize(size, st.vsync);
        size = presenter.swapchain().extent();
        restart = true;
      }
      // Dropped files replace the scene (the first one that loads).
      for (const std::string& path : window.takeDrops()) {
        auto next = scene::loadScene(path);
        if (!next) {
          st.message = next.error().message;
          continue;
        }
        vk.waitIdle();
        renderer.reset();
        scene = std::make_unique<scene::Scene>(std::move(*next));
        auto r = render::Renderer::create(vk, *scene);
        if (!r) return fail(r.error());
        renderer = std::move(*r);
        camera.reset(scene->cameras.front());
        st.selection = {};
        st.message = "loaded " + std::filesystem::path(path).filename().string();
        restart = true;
        break;
      }

#if RAYSTER_SHADER_HOT_RELOAD
      if (const ShaderReloadResult reload = shaderReloader.poll(); !reload.error.empty()) {
        st.message = reload.error;  // the old pipelines stay
        log::warn("shader reload: {}", reload.error);
      } else if (!reload.reloaded.empty()) {
        renderer->reloadPipelines();
        st.message = "reloaded " + std::to_string(reload.reloaded.size()) + " shader(s)";
        log::info("shader reload: {} shader(s) recompiled, pipelines rebuilt", reload.reloaded.size());
        restart = true;
      }
#endif
      const auto now = std::chrono::steady_clock::now();
      const float dt = std::chrono::duration<float>(now - last).count();
      last = now;
      recordHistory(st.cpuHistory, dt * 1000.0f);
      if (ui.build(st, camera, *scene, vk.info().name)) restart = true;
      if (!ui.wantsKeyboard()) {
        if (keys.pressed(w, GLFW_KEY_TAB)) showUi = !showUi;
        if (keys.pressed(w, GLFW_KEY_F)) st.frameScene = true;
        if (keys.pressed(w, GLFW_KEY_F12)) st.screenshot = true;
        if (keys.pressed(w, GLFW_KEY_P) && !scene->cameraPath.empty()) st.playPath = !st.playPath, restart = true;
        if (keys.pressed(w, GLFW_KEY_C))
          camera.mode = camera.mode == CameraMode::Orbit ? CameraMode::Fly : CameraMode::Orbit;
        if (keys.pressed(w, GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(w, GLFW_TRUE);
        for (int k = 0; k < 9; ++k)
          if (keys.pressed(w, GLFW_KEY_1 + k) && k < int(scene->cameras.size())) st.namedCamera = k;
      }
      if (st.lightsChanged) {
        renderer->refreshLights();
        cut = true;
      }
      if (st.namedCamera >= 0) {
        camera.reset(scene->cameras[size_t(st.namedCamera)]);
        st.namedCamera = -1;
        cut = true;
      }
      if (st.frameScene) {
        camera.frame(scene->bounds());
        st.frameScene = false;
        cut = true;
      }
      // Holding G moves the selection with the mouse instead of the camera.
      const bool grabbing = st.selection.instance >= 0 && !ui.wantsKeyboard() && glfwGetKey(w, GLFW_KEY_G) == GLFW_PRESS;
      if (const auto clicked = pick.update(w, !ui.wantsMouse() && !grabbing)) {
        std::vector<glm::mat4> transforms(scene->instances.size());
        for (size_t i = 0; i < transforms.size(); ++i) transforms[i] = renderer->instanceTransform(uint32_t(i));
        int ww = 0, wh = 0;
        glfwGetWindowSize(w, &ww, &wh);
        st.selection.instance = pickInstance(*scene, transforms, camera.camera(), *clicked, glm::vec2(ww, wh));
        if (st.selection.instance >= 0)
          st.selection.trs = decompose(transforms[size_t(st.selection.instance)]);
      }
      if (grabbing && pick.delta != glm::vec2(0.0f)) {
        int ww = 0, wh = 0;
        glfwGetWindowSize(w, &ww, &wh);
        st.selection.trs.position += dragOffset(camera.camera(), st.selection.trs.position, pick.delta, float(wh));
        st.selection.edited = true;
      }
      if (st.selection.edited && st.selection.instance >= 0)
        renderer->setInstanceTransform(uint32_t(st.selection.instance), compose(st.selection.trs));
      st.selection.edited = false;
      const bool moved =
          camera.update(w, dt, window.takeScroll(), !ui.wantsMouse() && !grabbing, !ui.wantsKeyboard());

      if (restart) {
        st.settings.width = size.width;
        st.settings.height = size.height;
        st.settings.cameraPath = st.playPath;
        st.settings.frames = UINT32_MAX;  // the run lasts until the next restart
        if (auto begun = renderer->beginRun(st.settings); !begun) {
          st.message = begun.error().message;
          st.settings.mode = render::Mode::Hybrid;  // fall back to what works
          st.settings.cameraPath = st.playPath = false;
          continue;
        }
        restart = false;
      }
      const bool lastFrame = o.frames && frame + 1 == o.frames;
      const bool shoot = (lastFrame && !o.screenshot.empty()) || st.screenshot;
      render::FrameControl control;
      if (!st.playPath) control.camera = camera.camera();
      control.cut = cut;
      control.moving = moved;
      control.present = true;
      control.readback = shoot || st.debugView != 0;
      cut = false;
      const render::FrameStats stats = renderer->renderFrame(control);
      if (failAt && failAt->second == frame) VK_CHECK(failAt->first);
      if (st.playPath) camera.reset(stats.camera);  // leaving the path continues from where it is
      st.passes.clear();
      for (const auto& p : stats.passes) st.passes.emplace_back(p.name, p.ms);
      recordHistory(st.gpuHistory, float(stats.gpuMs));
      st.raysPerFrame = frameRays(stats);
      st.deviceBytes = renderer->deviceBytesUsed();

      // A debug view shows one stage, read back and mapped for display as `--aov` PNGs are.
      std::optional<Image8> debugImage;
      if (st.debugView != 0) {
        render::RenderOutput images = renderer->readbackImages();
        if (!images.aovs.empty())
          debugImage = encodeSrgb8(aovForDisplay(images.aovs.front().first, std::move(images.aovs.front().second)));
        else
          st.message = "this scene has no " + render::aovNames()[size_t(st.debugView - 1)];
      }
      ImDrawData* drawData = ui.draw();
      Image8 captured;
      if (!presenter.present(renderer->outputImage(), showUi ? drawData : nullptr, shoot ? &captured : nullptr,
                             debugImage ? &*debugImage : nullptr))
        restart = true;  // out of date: the next iteration resizes
      if (shoot) {
        std::string path = lastFrame && !o.screenshot.empty() ? o.screenshot : "rayster-screenshot-" + std::to_string(frame) + ".png";
        const bool exr = std::filesystem::path(path).extension() == ".exr";
        render::RenderOutput out = renderer->endRun();
        restart = true;
        const ExrPixels pixels = o.exrFloat ? ExrPixels::Float : ExrPixels::Half;
        Status written = exr ? writeExr(path, out.hdr, pixels) : writePng(path, captured);
        if (!written) return fail(written.error());
        // A screenshot key press writes both: the window as shown, and the linear frame.
        if (!exr && st.screenshot)
          written = writeExr(std::filesystem::path(path).replace_extension(".exr"), out.hdr, pixels);
        st.message = written ? "wrote " + path : written.error().message;
        log::info("wrote {} ({}x{}, frame {})", path, captured.width, captured.height, frame + 1);
        st.screenshot = false;
      }
      ++frame;
      if (lastFrame) break;
    }
    vk.waitIdle();
    rhi::setFatalHook(nullptr);
    gShowFatal = nullptr;
  }
  if (vk.validationEnabled() && vk.validationErrors() > 0) {
    std::fprintf(stderr, "rayster: error: %u Vulkan validation error(s)\n", vk.validationErrors());
    return int(ExitCode::Failure);
  }
  return 0;
}

} // namespace rayster::app
