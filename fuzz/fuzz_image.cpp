// libFuzzer target for the image decoders Rayster reads files with (core/image_io.cpp: PNG and
// JPEG through stb_image, Radiance HDR through stb_image, EXR through tinyexr): any bytes must give
// an image or an Error, never a crash, hang or sanitizer report. The first byte picks the
// extension (.png, .hdr, .exr), the rest is the file. Run with scripts/fuzz.sh 60 fuzz_image.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "core/image_io.h"
#include "core/log.h"

namespace fs = std::filesystem;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const fs::path dir = [] {
    rayster::log::setLevel(rayster::log::Level::Error);
    fs::path d = fs::temp_directory_path() / ("rayster-fuzz-image-" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
  }();
  static const char* const kExtensions[] = {".png", ".hdr", ".exr"};
  const fs::path path = dir / (std::string("input") + kExtensions[data[0] % 3]);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  rayster::Result<rayster::ImageF> image = rayster::readImageLinear(path);
  if (image.ok() && image->rgba.size() != size_t(image->width) * size_t(image->height) * 4) std::abort();
  return 0;
}
