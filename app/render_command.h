#pragma once
#include <string>
#include <vector>

#include "app/fault_injection.h"
#include "render/renderer.h"

namespace rayster::app {

struct RenderOptions {
  std::string scene = "builtin:whitted";
  std::string output = "out/render.png";
  std::string hdrOutput;
  std::string jsonOutput;
  std::string aovs;  // comma-separated names, or "all"
  bool printTimings = false;
  bool memoryReport = false;  // --memory-report: the frame's images and their bytes
  bool validation = false;
  bool requireRt = false;  // --require-rt: exit MissingCapability instead of falling back to raster
  bool debugLabels = true;
  bool exrFloat = false;  // --exr-float: 32-bit float EXR channels instead of half
  // Whether --size / --frames (or --spp) were given: on a CPU device the others get smaller defaults.
  bool sizeGiven = false, framesGiven = false;
  std::string device;
  std::string variant;  // --variant: a KHR_materials_variants name ("": the default materials)
  render::RenderSettings settings;
  // Sequences (app/sequence.h): --frames-out A:B[:STEP] ("": one image), --skip-existing.
  std::string framesOut;
  bool skipExisting = false;
  std::string progress = "auto";  // --progress auto|bar|lines|off
  // Tests only: RAYSTER_RENDER_FAIL_AT's device loss or exhaustion (app/fault_injection.h).
  std::optional<InjectedFailure> failAt;
};

int renderCommand(const RenderOptions& options);

// The PNG of an AOV for looking at (normals as colours, decoded albedo, opaque alpha).
ImageF aovForDisplay(const std::string& name, ImageF img);

// --move-instance NAME:X,Y,Z@FRAME (render and view): at frame FRAME the instance moves to X,Y,Z.
Status parseMoves(const std::vector<std::string>& args, std::vector<render::RenderSettings::Move>& moves);

}  // namespace rayster::app
