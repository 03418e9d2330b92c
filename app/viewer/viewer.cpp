// The `rayster view` loop: input → panel → one renderer frame → present. The renderer is the same
// one `rayster render` drives (Renderer::beginRun/renderFrame); the window is just another consumer
// of its output image.
#include "app/viewer/viewer.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "app/viewer/camera_control.h"
#include "app/viewer/presenter.h"
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

// Rays per frame, estimated from the passes that ran: one ray per pixel per ray-generation pass
// and per shadowed light (the traced G-buffer's primaries included).
uint64_t estimateRays(const render::FrameStats& stats, uint32_t pixels, uint32_t shadowLayers) {
  uint64_t rays = 0;
  for (const auto& [name, ms] : stats.passes) {
    if (name == "rt-shadows") rays += uint64_t(pixels) * std::max(1u, shadowLayers);
    else if (name.rfind("rt-", 0) == 0 || name == "gbuffer-traced") rays += pixels;
  }
  return rays;
}

// Device loss and memory exhaustion end the process (rhi/vk_check.h); the window says why first.
GLFWwindow* gFatalWindow = nullptr;
void showFatal(const char* message) {
  if (!gFatalWindow) return;
  glfwSetWindowTitle(gFatalWindow, (std::string("Rayster: error: ") + message + " (exiting)").c_str());
  for (int i = 0; i < 30; ++i) glfwWaitEventsTimeout(0.1);  // three seconds to read it
}

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
    CameraControl camera;
    camera.reset(startCamera(*scene, o.settings.camera));
    bool showUi = !o.hideUi, restart = true, cut = false;
    KeyEdges keys;
    uint32_t frame = 0;
    auto last = std::chrono::steady_clock::now();
    GLFWwindow* w = window.handle();
    gFatalWindow = w;
    rhi::setFatalHook(showFatal);

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
        st.message = "loaded " + std::filesystem::path(path).filename().string();
        restart = true;
        break;
      }

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
      const bool moved = camera.update(w, dt, window.takeScroll(), !ui.wantsMouse(), !ui.wantsKeyboard());

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
      if (st.playPath) camera.reset(stats.camera);  // leaving the path continues from where it is
      st.passes = stats.passes;
      recordHistory(st.gpuHistory, float(stats.gpuMs));
      st.raysPerFrame = estimateRays(stats, size.width * size.height, std::min(8u, st.settings.shadowLights));
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
        Status written = exr ? writeExr(path, out.hdr) : writePng(path, captured);
        if (!written) return fail(written.error());
        // A screenshot key press writes both: the window as shown, and the linear frame.
        if (!exr && st.screenshot) written = writeExr(std::filesystem::path(path).replace_extension(".exr"), out.hdr);
        st.message = written ? "wrote " + path : written.error().message;
        log::info("wrote {} ({}x{}, frame {})", path, captured.width, captured.height, frame + 1);
        st.screenshot = false;
      }
      ++frame;
      if (lastFrame) break;
    }
    vk.waitIdle();
    rhi::setFatalHook(nullptr);
    gFatalWindow = nullptr;
  }
  if (vk.validationEnabled() && vk.validationErrors() > 0) {
    std::fprintf(stderr, "rayster: error: %u Vulkan validation error(s)\n", vk.validationErrors());
    return int(ExitCode::Failure);
  }
  return 0;
}

} // namespace rayster::app
