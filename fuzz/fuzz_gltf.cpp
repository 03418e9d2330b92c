// libFuzzer target for the glTF loader: the bytes become a .glb (when they start with the GLB
// magic) or a .gltf in a per-process folder, then loadGltf. Only crashes, hangs, leaks and
// sanitizer reports count; refusals are the expected outcome for most inputs.
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/log.h"
#include "scene/animation.h"
#include "scene/gltf_loader.h"

namespace {

const std::filesystem::path& workDir() {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d =
        std::filesystem::temp_directory_path() / ("rayster-fuzz-gltf-" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    rayster::log::setLevel(rayster::log::Level::Error);  // refusals warn; thousands of lines help no one
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::filesystem::path path = workDir() / (glb ? "input.glb" : "input.gltf");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  rayster::Result<rayster::scene::Scene> scene = rayster::scene::loadGltf(path);
  // Whatever the loader accepts must also play: sample before, inside and after the keys.
  if (scene.ok() && scene->animated())
    for (float t : {-1.0f, 0.0f, 0.5f, 1.7f, 1e6f}) rayster::scene::evaluateAnimations(*scene, t, t > 1.0f);
  return 0;
}
