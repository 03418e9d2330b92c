#pragma once
#include <string>

#include "render/renderer.h"

namespace rayster::app {

struct RenderOptions {
  std::string scene = "builtin:cornell";
  std::string output = "out/render.png";
  std::string hdrOutput;
  std::string jsonOutput;
  bool printTimings = false;
  bool validation = false;
  std::string device;
  render::RenderSettings settings;
};

int renderCommand(const RenderOptions& options);
int infoCommand();

} // namespace rayster::app
