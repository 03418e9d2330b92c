// Command-line parsing of `rayster view`.
#include <algorithm>
#include <cstdio>

#include <CLI/CLI.hpp>

#include "app/render_command.h"
#include "app/settings_cli.h"
#include "app/viewer/viewer.h"
#include "core/error.h"

namespace rayster::app {

int runViewer(const ViewOptions& options);

void addViewCommand(CLI::App& cli, ViewCommand& v) {
  CLI::App* view = cli.add_subcommand("view", "Open a window: camera controls, settings panel, per-pass GPU timings");
  v.app = view;
  ViewOptions& o = v.options;
  view->add_option("scene", o.scene, "Scene file (.gltf/.glb, .obj, .json) or builtin:NAME; default builtin:whitted");
  view->add_option("--size", v.size, "Window size WxH (default 1280x720)");
  view->add_option("--frames", o.frames, "Close after this many frames (scripted runs and tests)");
  view->add_option("--screenshot", o.screenshot,
                   "After the last frame write the presented window image (.png, with the panel unless --hide-ui)");
  view->add_flag("--exr-float", o.exrFloat, "Write screenshot EXRs with 32-bit float channels instead of half floats");
  view->add_option("--resize-at", v.resizeAt, "Resize the window at frame F to WxH (F:WxH, repeatable)");
  view->add_flag("--hide-ui", o.hideUi, "Start with the panel hidden (Tab toggles it)");
  view->add_flag("--vsync{true},--no-vsync{false}", o.vsync, "Present with vsync (default) or without");
  view->add_option("--camera", o.settings.camera, "Start from this named camera");
  // The viewer starts from raster primaries (auto would time both producers at every restart).
  o.settings.primary = render::Primary::Raster;
  addSettingOptions(view, render::kUseView, v.settings, o.settings);
  view->add_option("--seed", o.settings.seed, "Random seed");
  view->add_flag("--camera-path", o.settings.cameraPath, "Play the scene's camera path");
  view->add_option("--path-fps", o.settings.pathFps, "Frames per second of path playback (default 60)")
      ->check(CLI::Range(1.0f, 10000.0f));
  view->add_option("--move-instance", v.moveInstance,
                   "At frame FRAME move the named instance to X,Y,Z: NAME:X,Y,Z@FRAME (repeatable; scripted tests)");
  view->add_option("--debug-view", o.debugView,
                   "Show this stage instead of the final image (the panel's view list, e.g. normal, motion)");
  view->fallthrough();
}

int viewCommand(ViewCommand& v, bool validation, const std::string& device, bool debugLabels) {
  ViewOptions& o = v.options;
  auto bad = [](const std::string& what) {
    std::fprintf(stderr, "rayster: error: %s\n", what.c_str());
    return int(ExitCode::BadArguments);
  };
  unsigned w = 0, h = 0, f = 0;
  char x = 0, extra = 0;
  if (std::sscanf(v.size.c_str(), "%u%c%u%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || !w || !h ||
      w > 16384 || h > 16384)
    return bad("--size must be WxH with 1..16384 each, got '" + v.size + "'");
  o.width = w;
  o.height = h;
  for (const std::string& r : v.resizeAt) {
    if (std::sscanf(r.c_str(), "%u:%u%c%u%c", &f, &w, &x, &h, &extra) != 4 || (x != 'x' && x != 'X') || !w || !h ||
        w > 16384 || h > 16384)
      return bad("--resize-at must be F:WxH, got '" + r + "'");
    o.resizes.push_back({f, w, h});
  }
  if (!o.screenshot.empty() && o.screenshot.size() < 4) return bad("--screenshot must end in .png or .exr");
  if (Status m = parseMoves(v.moveInstance, o.settings.moves); !m) return bad(m.error().message);
  const auto& aovs = render::aovNames();
  if (!o.debugView.empty() && std::find(aovs.begin(), aovs.end(), o.debugView) == aovs.end())
    return bad("--debug-view: unknown view '" + o.debugView + "'");
  if (Status applied = applySettings(v.settings, o.settings); !applied) return bad(applied.error().message);
  o.validation = validation;
  o.device = device;
  o.debugLabels = debugLabels;
  return runViewer(o);
}

}  // namespace rayster::app
