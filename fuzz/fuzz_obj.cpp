// libFuzzer target for the OBJ loader: any bytes must give a Scene or an Error, never a crash,
// hang or sanitizer report. Run with scripts/fuzz.sh 60 fuzz_obj.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "core/log.h"
#include "scene/obj_loader.h"

namespace fs = std::filesystem;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // One folder per process: libFuzzer's -jobs/-workers run several processes side by side.
  static const fs::path dir = [] {
    rayster::log::setLevel(rayster::log::Level::Error);  // missing .mtl warnings would flood the output
    fs::path d = fs::temp_directory_path() / ("rayster-fuzz-obj-" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
  }();
  const fs::path path = dir / "input.obj";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  rayster::Result<rayster::scene::Scene> scene = rayster::scene::loadObj(path);
  if (scene.ok()) {
    // A loaded scene must be one the renderer can take (validate() wants a camera it cannot get here).
    rayster::scene::Scene s = std::move(scene.value());
    s.cameras.emplace_back();
    rayster::Status valid = rayster::scene::validate(s);
    if (!valid.ok()) {
      std::fprintf(stderr, "loadObj produced an invalid scene: %s\n", valid.error().message.c_str());
      std::abort();
    }
  }
  return 0;
}
