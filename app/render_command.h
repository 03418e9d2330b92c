#pragma once
#include <string>

#include "render/renderer.h"

namespace rayster::app {

struct RenderOptions {
  std::string scene = "builtin:whitted";
  std::string output = "out/render.png";
  std::string hdrOutput;
  std::string jsonOutput;
  std::string aovs;  // comma-separated names, or "all"
  bool printTimings = false;
  bool validation = false;
  bool requireRt = false;  // --require-rt: exit MissingCapability instead of falling back to raster
  bool debugLabels = true;
  std::string device;
  render::RenderSettings settings;
};

int renderCommand(const RenderOptions& options);

int infoCommand();

} // namespace rayster::app
