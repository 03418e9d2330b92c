#include "app/viewer/ui.h"

#include "render/settings_table.h"

#include <algorithm>

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include "rhi/commands.h"
#include "rhi/context.h"
#include "rhi/vk_check.h"

namespace rayster::app {
namespace {

constexpr size_t kHistoryFrames = 240;  // rolling graph: a few seconds at interactive rates
constexpr float kPanelWidth = 300.0f;

void checkResult(VkResult r) { VK_CHECK(r); }

}  // namespace

Ui::Ui(rhi::Context& ctx, GLFWwindow* window, VkRenderPass pass, uint32_t minImages, uint32_t images) : ctx_(ctx) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 4.0f;
  ImGui_ImplGlfw_InitForVulkan(window, true);

  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pci.maxSets = 16;
  pci.poolSizeCount = 1;
  pci.pPoolSizes = &size;
  VK_CHECK(vkCreateDescriptorPool(ctx.device(), &pci, nullptr, &pool_));

  // The backend is compiled without prototypes (volk owns the vk* names): hand it volk's loader.
  VkInstance instance = ctx.instance();
  ImGui_ImplVulkan_LoadFunctions(
      [](const char* name, void* user) { return vkGetInstanceProcAddr(*static_cast<VkInstance*>(user), name); },
      &instance);
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = ctx.instance();
  info.PhysicalDevice = ctx.physicalDevice();
  info.Device = ctx.device();
  info.QueueFamily = ctx.queueFamily();
  info.Queue = ctx.queue();
  info.DescriptorPool = pool_;
  info.MinImageCount = minImages;
  info.ImageCount = images;
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = checkResult;
  ImGui_ImplVulkan_Init(&info, pass);
  rhi::OneShot upload(ctx);
  ImGui_ImplVulkan_CreateFontsTexture(upload);
  upload.submitAndWait();
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

Ui::~Ui() {
  ctx_.waitIdle();
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  vkDestroyDescriptorPool(ctx_.device(), pool_, nullptr);
}

bool Ui::wantsMouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool Ui::wantsKeyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

ImDrawData* Ui::draw() {
  ImGui::Render();
  frameOpen_ = false;
  return ImGui::GetDrawData();
}

ImDrawData* Ui::drawMessage(const std::string& message) {
  if (frameOpen_) ImGui::EndFrame();
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos({0, 0});
  ImGui::SetNextWindowSize(size);
  ImGui::Begin("##fatal", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings);
  ImGui::SetWindowFontScale(2.0f);
  ImGui::SetCursorPosY(size.y * 0.4f);
  ImGui::PushTextWrapPos(size.x - 16.0f);
  ImGui::TextColored({1.0f, 0.4f, 0.3f, 1.0f}, "Rayster: error: %s", message.c_str());
  ImGui::PopTextWrapPos();
  ImGui::SetWindowFontScale(1.0f);
  ImGui::TextUnformatted("The viewer exits in a few seconds.");
  ImGui::End();
  ImGui::Render();
  frameOpen_ = false;
  return ImGui::GetDrawData();
}

namespace {

// The settings table's viewer entries of one group (render/settings_table.h): a checkbox per
// switch, a combo per choice, a slider per number, each with the table's help as its tooltip.
void settingWidgets(const char* group, render::RenderSettings& s) {
  for (const render::Setting& setting : render::settingsTable()) {
    if (setting.group != group || (setting.uses & render::kUseView) == 0) continue;
    const std::string value = setting.get(s);
    const char* label = setting.name.c_str();
    std::string next = value;
    switch (setting.kind) {
      case render::SettingKind::Switch: {
        bool on = value == "on";
        if (ImGui::Checkbox(label, &on)) next = on ? "on" : "off";
        break;
      }
      case render::SettingKind::Choice:
        if (ImGui::BeginCombo(label, value.c_str())) {
          for (const std::string& c : setting.choices)
            if (ImGui::Selectable(c.c_str(), c == value)) next = c;
          ImGui::EndCombo();
        }
        break;
      case render::SettingKind::Integer: {
        int v = std::stoi(value);
        if (ImGui::SliderInt(label, &v, int(setting.min), int(std::min(setting.max, 64.0)))) next = std::to_string(v);
        break;
      }
      case render::SettingKind::Real: {
        // A named value ("auto", "off") is a checkbox that, unticked, gives the number a slider.
        // Unbounded ranges get a slider over a sensible span; the command line takes any value.
        const float lo = float(std::max(setting.min, -20.0)), hi = float(std::min(setting.max, 20.0));
        const bool named = std::find(setting.choices.begin(), setting.choices.end(), value) != setting.choices.end();
        if (!setting.choices.empty()) {
          const std::string& name = setting.choices.front();
          bool isNamed = named;
          if (ImGui::Checkbox((setting.name + " " + name).c_str(), &isNamed))
            next = isNamed ? name : std::to_string(std::clamp(0.0f, lo, hi));
          if (named) break;
        }
        float v = std::stof(value);
        if (ImGui::SliderFloat(label, &v, lo, hi, "%.2f")) next = std::to_string(v);
        break;
      }
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", setting.help.c_str());
    if (next != value) (void)setting.set(s, next);  // widgets stay in range: set() cannot fail here
  }
}

// Whether a change from `a` to `b` restarts accumulation (the table's `restarts`).
bool restarts(const render::RenderSettings& a, const render::RenderSettings& b) {
  for (const render::Setting& setting : render::settingsTable())
    if (setting.restarts && setting.get(a) != setting.get(b)) return true;
  return false;
}

}  // namespace

bool Ui::build(PanelState& st, CameraControl& camera, scene::Scene& scene, const std::string& device) {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  frameOpen_ = true;
  render::RenderSettings& s = st.settings;
  const render::RenderSettings before = s;
  ImGui::SetNextWindowPos({8, 8}, ImGuiCond_FirstUseEver);
  // The panel fits its contents, up to the window's height (then it scrolls).
  ImGui::SetNextWindowSizeConstraints({kPanelWidth, 0.0f}, {kPanelWidth, ImGui::GetIO().DisplaySize.y - 16.0f});
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("Rayster", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::PushItemWidth(kPanelWidth * 0.5f);
  if (!st.message.empty()) ImGui::TextColored({1.0f, 0.4f, 0.3f, 1.0f}, "%s", st.message.c_str());
  ImGui::Text("%s", device.c_str());
  ImGui::Text("%ux%u  %.1f ms CPU  %.2f ms GPU", s.width, s.height, st.cpuHistory.empty() ? 0.0f : st.cpuHistory.back(),
              st.gpuHistory.empty() ? 0.0f : st.gpuHistory.back());
  ImGui::Text("%.2f Mrays/frame  %.1f MiB device memory", double(st.raysPerFrame) / 1e6,
              double(st.deviceBytes) / (1 << 20));

  if (ImGui::CollapsingHeader("Render", ImGuiTreeNodeFlags_DefaultOpen)) {
    settingWidgets("Render", s);
    ImGui::Checkbox("vsync", &st.vsync);
    // Every G-buffer channel and every pass's raw and denoised output (render::aovNames()).
    const auto& names = render::aovNames();
    const char* current = st.debugView == 0 ? "final image" : names[size_t(st.debugView - 1)].c_str();
    if (ImGui::BeginCombo("view", current)) {
      if (ImGui::Selectable("final image", st.debugView == 0)) st.debugView = 0;
      for (size_t i = 0; i < names.size(); ++i)
        if (ImGui::Selectable(names[i].c_str(), st.debugView == int(i + 1))) st.debugView = int(i + 1);
      ImGui::EndCombo();
    }
  }
  if (ImGui::CollapsingHeader("Effects")) settingWidgets("Effects", s);
  if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) {
    int mode = int(camera.mode);
    ImGui::Combo("control", &mode, "orbit\0fly (WASD/QE)\0");
    camera.mode = CameraMode(mode);
    if (camera.mode == CameraMode::Fly)
      ImGui::SliderFloat("speed", &camera.flySpeed, 0.01f, 100.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    if (ImGui::Button("frame scene (F)")) st.frameScene = true;
    ImGui::SameLine();
    if (ImGui::Button("screenshot (F12)")) st.screenshot = true;
    for (size_t i = 0; i < scene.cameras.size(); ++i) {
      const std::string label = (i < 9 ? std::to_string(i + 1) + ": " : "") +
                                (scene.cameras[i].name.empty() ? "camera " + std::to_string(i) : scene.cameras[i].name);
      if (ImGui::Selectable(label.c_str(), false)) st.namedCamera = int(i);
    }
    if (!scene.cameraPath.empty()) ImGui::Checkbox("play camera path (P)", &st.playPath);
  }
  st.lightsChanged = false;
  if (!scene.lights.empty() && ImGui::CollapsingHeader("Lights")) {
    for (size_t i = 0; i < scene.lights.size(); ++i) {
      scene::Light& l = scene.lights[i];
      ImGui::PushID(int(i));
      if (ImGui::TreeNode(l.name.empty() ? ("light " + std::to_string(i)).c_str() : l.name.c_str())) {
        bool& c = st.lightsChanged;
        if (l.type != scene::LightType::Directional) c |= ImGui::DragFloat3("position", &l.position.x, 0.05f);
        c |= ImGui::ColorEdit3("colour", &l.color.x);
        c |= ImGui::DragFloat("intensity", &l.intensity, 0.05f * std::max(1.0f, l.intensity), 0.0f, 1e7f);
        c |= ImGui::DragFloat("radius", &l.radius, 0.005f, 0.0f, 100.0f);
        ImGui::TreePop();
      }
      ImGui::PopID();
    }
  }
  if (ImGui::CollapsingHeader("Selection", ImGuiTreeNodeFlags_DefaultOpen)) {
    Selection& sel = st.selection;
    if (sel.instance < 0 || size_t(sel.instance) >= scene.instances.size()) {
      ImGui::TextDisabled("click an object to select it");
    } else {
      const std::string& name = scene.instances[size_t(sel.instance)].name;
      ImGui::Text("%s", name.empty() ? ("instance " + std::to_string(sel.instance)).c_str() : name.c_str());
      bool& e = sel.edited;
      e |= ImGui::DragFloat3("position", &sel.trs.position.x, 0.01f);
      e |= ImGui::DragFloat3("rotation", &sel.trs.rotationDeg.x, 0.5f, -360.0f, 360.0f, "%.1f");
      e |= ImGui::DragFloat3("scale", &sel.trs.scale.x, 0.01f, 0.001f, 1000.0f);
      ImGui::TextDisabled("hold G and move the mouse to move it");
      if (ImGui::Button("deselect")) sel.instance = -1;
    }
  }
  if (ImGui::CollapsingHeader("GPU timings", ImGuiTreeNodeFlags_DefaultOpen)) {
    double longest = 0.0;
    for (const auto& [name, ms] : st.passes) longest = std::max(longest, ms);
    for (const auto& [name, ms] : st.passes) {
      char overlay[64];
      std::snprintf(overlay, sizeof overlay, "%.3f ms", ms);
      ImGui::ProgressBar(longest > 0 ? float(ms / longest) : 0.0f, {kPanelWidth * 0.45f, 0.0f}, overlay);
      ImGui::SameLine();
      ImGui::TextUnformatted(name.c_str());
    }
    std::vector<float> gpu(st.gpuHistory.begin(), st.gpuHistory.end());
    if (!gpu.empty())
      ImGui::PlotLines("##gpu", gpu.data(), int(gpu.size()), 0, "GPU ms per frame", 0.0f, FLT_MAX,
                       {kPanelWidth - 20, 60});
  }
  ImGui::PopItemWidth();
  ImGui::End();
  // Render settings that change the image restart the run; vsync and the camera do not.
  s.aovs = st.debugView ? std::vector<std::string>{render::aovNames()[size_t(st.debugView - 1)]}
                        : std::vector<std::string>{};
  return before.aovs != s.aovs || restarts(before, s);
}

void recordHistory(std::deque<float>& history, float value) {
  history.push_back(value);
  while (history.size() > kHistoryFrames) history.pop_front();
}

}  // namespace rayster::app
