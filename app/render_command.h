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

struct CompareOptions {
  std::string reference, test, heatmap;
  int tolerance = 2;
  double minFraction = -1.0;  // < 0: report only
};
int compareCommand(const CompareOptions& options);
int infoCommand();

} // namespace rayster::app
