#pragma once
// `rayster view`: the interactive window. Scripted runs (--frames, --screenshot, --resize-at) make
// it testable under Xvfb.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "render/renderer.h"

namespace CLI {
class App;
}

namespace rayster::app {

struct ViewOptions {
  std::string scene = "builtin:whitted";
  uint32_t width = 1280, height = 720;
  uint32_t frames = 0;     // 0: run until the window closes
  std::string screenshot;  // after the last frame: the presented image (.png); .exr: the HDR frame
  struct Resize {
    uint32_t frame, width, height;
  };
  std::vector<Resize> resizes;  // --resize-at F:WxH
  std::string debugView;        // --debug-view NAME: start showing this stage (render::aovNames())
  bool hideUi = false;
  bool vsync = true;
  bool exrFloat = false;  // --exr-float: screenshot EXRs with 32-bit float channels
  bool validation = false;
  bool debugLabels = true;
  std::string device;
  render::RenderSettings settings;
};

// Adds the `view` subcommand; the returned function finishes parsing and runs it.
struct ViewCommand {
  CLI::App* app = nullptr;
  ViewOptions options;
  std::string size = "1280x720";
  std::map<std::string, std::string> settings;  // the settings table's options given (app/settings_cli.h)
  std::vector<std::string> resizeAt;
  std::vector<std::string> moveInstance;
};
void addViewCommand(CLI::App& cli, ViewCommand& view);
int viewCommand(ViewCommand& view, bool validation, const std::string& device, bool debugLabels);

}  // namespace rayster::app
