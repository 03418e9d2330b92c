// libFuzzer target for the JSON scene files (scene/scene_file.cpp): any bytes must give a Scene or
// an Error, never a crash, hang or sanitizer report. The input is written as scene.json next to a
// small OBJ and HDR it may name (quad.obj, sky.hdr), so models and environments are reached too.
// Run with scripts/fuzz.sh 60 fuzz_scene_file.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "core/image_io.h"
#include "core/log.h"
#include "scene/scene_file.h"

namespace fs = std::filesystem;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const fs::path dir = [] {
    rayster::log::setLevel(rayster::log::Level::Error);  // unknown keys warn; that would flood the output
    fs::path d = fs::temp_directory_path() / ("rayster-fuzz-scene-" + std::to_string(getpid()));
    fs::create_directories(d);
    std::ofstream(d / "quad.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    rayster::ImageF sky = rayster::ImageF::make(4, 2);
    for (float& v : sky.rgba) v = 0.5f;
    (void)rayster::writeImage(d / "sky.hdr", sky);
    return d;
  }();
  const fs::path path = dir / "scene.json";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  rayster::Result<rayster::scene::Scene> scene = rayster::scene::loadSceneFile(path);
  if (scene.ok()) {
    rayster::scene::Scene s = std::move(scene.value());
    if (s.cameras.empty()) s.cameras.emplace_back();
    rayster::Status valid = rayster::scene::validate(s);
    if (!valid.ok()) {
      std::fprintf(stderr, "loadSceneFile produced an invalid scene: %s\n", valid.error().message.c_str());
      std::abort();
    }
  }
  return 0;
}
