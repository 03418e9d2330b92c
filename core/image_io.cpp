#include "core/image_io.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

// stb_image's implementation is core/stb_impl.cpp.
#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>

#include "core/interrupt.h"
#include "core/log.h"

namespace fs = std::filesystem;

namespace rayster {
namespace {

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// strerror's reasons start with a capital ("No space left on device"); mid-line they read lower.
Error writeError(const fs::path& path, std::string reason) {
  if (reason.size() > 1 && std::isupper(static_cast<unsigned char>(reason[0])) &&
      std::islower(static_cast<unsigned char>(reason[1])))
    reason[0] = char(std::tolower(static_cast<unsigned char>(reason[0])));
  return makeError(ExitCode::OutputFailed, "cannot write {}: {}", path.string(), reason);
}

// Runs `produce(tempPath)` and renames the result over `path`. The temp file lives in the same
// folder so the rename is atomic (same filesystem); the pid keeps parallel test runs apart.
template <class Produce>
Status writeAtomically(const fs::path& path, Produce&& produce) {
  std::error_code ec;
  const fs::path parent = path.parent_path();
  if (!parent.empty() && !fs::exists(parent, ec)) {
    fs::create_directories(parent, ec);
    if (ec) return writeError(path, "cannot create folder " + parent.string() + ": " + ec.message());
  }
  fs::path temp = path;
  temp += ".tmp-" + std::to_string(::getpid());
  const TempFileInProgress tracked(temp);  // a second SIGINT/SIGTERM unlinks it (core/interrupt.h)
  std::string reason;
  if (!produce(temp, reason)) {
    fs::remove(temp, ec);
    return writeError(path, reason);
  }
  fs::rename(temp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    return writeError(path, ec.message());
  }
  return okStatus();
}

bool writeBytes(const fs::path& path, const std::vector<uint8_t>& bytes, std::string& reason) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) {
    reason = std::strerror(errno);
    return false;
  }
  const size_t written = std::fwrite(bytes.data(), 1, bytes.size(), file);
  const int writeErrno = errno;
  // fclose flushes: a full disk often shows up only here.
  const bool closed = std::fclose(file) == 0;
  if (written != bytes.size() || !closed) {
    reason = std::strerror(written != bytes.size() ? writeErrno : errno);
    return false;
  }
  return true;
}

void appendToVector(void* context, void* data, int size) {
  auto* bytes = static_cast<std::vector<uint8_t>*>(context);
  auto* begin = static_cast<const uint8_t*>(data);
  bytes->insert(bytes->end(), begin, begin + size);
}

Error readError(const fs::path& path, const std::string& reason) {
  return makeError(ExitCode::BadInput, "cannot read {}: {}", path.string(), reason);
}

// Distinguishes "missing" from "corrupt" before a decoder reports something vague.
std::optional<Error> checkReadable(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return readError(path, "no such file");
  if (!fs::is_regular_file(path, ec)) return readError(path, "not a regular file");
  return std::nullopt;
}

// Reads the whole file (stb then decodes from memory, after stbDecodeHazard()).
std::optional<std::vector<uint8_t>> readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Images larger than this are refused before decoding: a header can claim any size, and the
// decoders allocate what it claims (16384 per side is the glTF and OBJ textures' limit too).
constexpr int64_t kMaxReadSide = 16384;
constexpr int64_t kMaxReadPixels = int64_t(1) << 28;

std::optional<Error> checkDimensions(const fs::path& path, int64_t w, int64_t h) {
  if (w > kMaxReadSide || h > kMaxReadSide || w * h > kMaxReadPixels)
    return readError(path, fmt::format("{}x{} pixels, more than {} per side", w, h, kMaxReadSide));
  return std::nullopt;
}

// The size a PNG, JPEG or HDR header claims, checked before stb allocates it, and the bytes stb
// must not see.
std::optional<Error> checkStbInput(const fs::path& path, const std::vector<uint8_t>& bytes) {
  if (const std::string hazard = stbDecodeHazard(bytes.data(), bytes.size()); !hazard.empty())
    return readError(path, hazard);
  int w = 0, h = 0, channels = 0;
  if (bytes.size() > size_t(INT_MAX) || !stbi_info_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels))
    return std::nullopt;  // the decoder says why
  return checkDimensions(path, w, h);
}

// The same for an EXR's data window.
std::optional<Error> checkExrDimensions(const fs::path& path) {
  EXRVersion version;
  if (ParseEXRVersionFromFile(&version, path.c_str()) != TINYEXR_SUCCESS) return std::nullopt;
  EXRHeader header;
  InitEXRHeader(&header);
  const char* err = nullptr;
  std::optional<Error> result;
  if (ParseEXRHeaderFromFile(&header, &version, path.c_str(), &err) == TINYEXR_SUCCESS) {
    const EXRBox2i& d = header.data_window;
    result = checkDimensions(path, int64_t(d.max_x) - d.min_x + 1, int64_t(d.max_y) - d.min_y + 1);
  }
  FreeEXRHeader(&header);  // a header that failed to parse may hold what it read so far
  if (err) FreeEXRErrorMessage(err);
  return result;
}

const std::array<float, 256>& srgbDecodeTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = srgbToLinear(static_cast<float>(i) / 255.0f);
    return t;
  }();
  return table;
}

uint8_t quantize(float value) {
  if (!(value > 0.0f)) return 0;  // also catches NaN
  if (value >= 1.0f) return 255;
  return static_cast<uint8_t>(std::lround(value * 255.0f));
}

// The largest finite half float; anything larger (from 65520 up) rounds to inf when converted.
constexpr float kHalfMax = 65504.0f;

struct FiniteCounts {
  size_t clamped = 0, nan = 0;
};

// Clamps every value to [-limit, limit] and replaces NaN by 0. Why 0: a NaN carries no value to
// keep, and 0 is what the PNG encoder writes for it (encodeSrgb8), so the EXR and PNG of one render
// agree; it also keeps the sums of `rayster compare` and of compositing filters finite.
FiniteCounts makeFinite(ImageF& image, float limit) {
  FiniteCounts counts;
  for (float& v : image.rgba) {
    if (std::isnan(v)) {
      v = 0.0f;
      ++counts.nan;
    } else if (v > limit || v < -limit) {
      v = std::clamp(v, -limit, limit);
      ++counts.clamped;
    }
  }
  return counts;
}

Result<ImageF> readHdr(const fs::path& path) {
  if (auto error = checkReadable(path)) return *error;
  const std::optional<std::vector<uint8_t>> bytes = readBytes(path);
  if (!bytes) return readError(path, "cannot open");
  if (auto error = checkStbInput(path, *bytes)) return *error;
  int w = 0, h = 0, channels = 0;
  float* data = stbi_loadf_from_memory(bytes->data(), int(bytes->size()), &w, &h, &channels, 4);
  if (!data) return readError(path, stbi_failure_reason() ? stbi_failure_reason() : "decode failed");
  ImageF image = ImageF::make(w, h);
  std::copy(data, data + image.rgba.size(), image.rgba.begin());
  stbi_image_free(data);
  return image;
}

Status writeHdr(const fs::path& path, const ImageF& image) {
  return writeAtomically(path, [&](const fs::path& temp, std::string& reason) {
    std::vector<uint8_t> bytes;
    if (!stbi_write_hdr_to_func(appendToVector, &bytes, image.width, image.height, 4, image.rgba.data())) {
      reason = "Radiance HDR encoding failed";
      return false;
    }
    return writeBytes(temp, bytes, reason);
  });
}

// What tinyexr's SaveEXR writes (RGBA stored as ABGR planes; uncompressed below 16x16, ZIP
// otherwise), into memory. Empty on failure, with `error` set.
std::vector<uint8_t> encodeExr(const ImageF& image, bool half, std::string& error) {
  const size_t pixels = size_t(image.width) * image.height;
  std::vector<float> planes[4];
  for (int c = 0; c < 4; ++c) {
    planes[c].resize(pixels);
    for (size_t i = 0; i < pixels; ++i) planes[c][i] = image.rgba[i * 4 + c];
  }
  float* abgr[4] = {planes[3].data(), planes[2].data(), planes[1].data(), planes[0].data()};
  EXRImage exr;
  InitEXRImage(&exr);
  exr.num_channels = 4;
  exr.images = reinterpret_cast<unsigned char**>(abgr);
  exr.width = image.width;
  exr.height = image.height;
  EXRHeader header;
  InitEXRHeader(&header);
  header.compression_type =
      image.width < 16 && image.height < 16 ? TINYEXR_COMPRESSIONTYPE_NONE : TINYEXR_COMPRESSIONTYPE_ZIP;
  EXRChannelInfo channels[4] = {};
  int pixelTypes[4], requestedTypes[4];
  for (int c = 0; c < 4; ++c) {
    channels[c].name[0] = "ABGR"[c];
    pixelTypes[c] = TINYEXR_PIXELTYPE_FLOAT;
    requestedTypes[c] = half ? TINYEXR_PIXELTYPE_HALF : TINYEXR_PIXELTYPE_FLOAT;
  }
  header.num_channels = 4;
  header.channels = channels;
  header.pixel_types = pixelTypes;
  header.requested_pixel_types = requestedTypes;
  unsigned char* memory = nullptr;
  const char* err = nullptr;
  const size_t size = SaveEXRImageToMemory(&exr, &header, &memory, &err);
  std::vector<uint8_t> bytes;
  if (size > 0 && memory) bytes.assign(memory, memory + size);
  std::free(memory);
  if (bytes.empty()) error = err ? err : "EXR encoding failed";
  if (err) FreeEXRErrorMessage(err);
  return bytes;
}

}  // namespace

std::string stbDecodeHazard(const uint8_t* d, size_t n) {
  // Only JPEG has the problem. stb takes any run of 0xFF fill bytes before the SOI marker (as
  // before every marker), so a file may start 0xFF 0xFF ... 0xD8.
  if (n < 4 || d[0] != 0xFF) return {};
  size_t i = 1;
  while (i < n && d[i] == 0xFF) ++i;
  if (i >= n || d[i] != 0xD8) return {};
  ++i;
  // Walk the markers; inside entropy-coded data only 0xFF 0x00 (a stuffed byte), RSTn and fill
  // bytes follow an 0xFF, so a byte-wise scan for the next marker is enough.
  while (i + 4 <= n) {
    if (d[i] != 0xFF || d[i + 1] == 0xFF) {
      ++i;
      continue;
    }
    const uint8_t marker = d[i + 1];
    if (marker == 0x00 || marker == 0x01 || marker == 0xD8 || (marker >= 0xD0 && marker <= 0xD7)) {
      i += 2;
      continue;
    }
    if (marker == 0xD9) break;  // end of image
    const size_t length = size_t(d[i + 2]) << 8 | d[i + 3];
    if (marker == 0xC4) {
      // DHT: tables of a class/id byte, 16 code counts, then the symbols, read the way stb reads
      // them: while the segment's length is not used up, even past its end.
      int64_t remaining = int64_t(length) - 2;
      for (size_t p = i + 4; remaining > 0;) {
        size_t codes = 0;
        for (size_t k = 1; k <= 16; ++k) codes += p + k < n ? d[p + k] : 0;
        if (codes > 256) return fmt::format("a JPEG Huffman table declares {} codes (at most 256)", codes);
        p += 17 + codes;
        remaining -= int64_t(17 + codes);
      }
    }
    i += 2 + std::max<size_t>(length, 2);
  }
  return {};
}

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

float linearToSrgb(float l) { return l <= 0.0031308f ? l * 12.92f : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f; }

Status writePng(const fs::path& path, const Image8& image) {
  if (image.empty()) return writeError(path, "image is empty");
  return writeAtomically(path, [&](const fs::path& temp, std::string& reason) {
    std::vector<uint8_t> bytes;
    if (!stbi_write_png_to_func(appendToVector, &bytes, image.width, image.height, 4, image.rgba.data(),
                                image.width * 4)) {
      reason = "PNG encoding failed";
      return false;
    }
    return writeBytes(temp, bytes, reason);
  });
}

Status writeExr(const fs::path& path, const ImageF& image, ExrPixels pixels) {
  if (image.empty()) return writeError(path, "image is empty");
  const bool half = pixels == ExrPixels::Half;
  ImageF finite = image;
  const FiniteCounts changed = makeFinite(finite, half ? kHalfMax : FLT_MAX);
  if (changed.clamped > 0)
    log::warn("{}: {} value(s) beyond {} clamped to {}{}", path.string(), changed.clamped,
              half ? "the half-float range" : "the float range", half ? "65504" : "the largest float",
              half ? " (--exr-float writes 32-bit floats)" : "");
  if (changed.nan > 0) log::warn("{}: {} NaN value(s) written as 0", path.string(), changed.nan);
  // Encoded in memory and written by writeBytes, which checks fclose: tinyexr's own file writer
  // ignores it, and a full disk often fails only there (it renamed a truncated file into place).
  std::string encodeError;
  const std::vector<uint8_t> bytes = encodeExr(finite, half, encodeError);
  if (bytes.empty()) return writeError(path, encodeError);
  return writeAtomically(path,
                         [&](const fs::path& temp, std::string& reason) { return writeBytes(temp, bytes, reason); });
}

Result<Image8> readPng(const fs::path& path) {
  if (auto error = checkReadable(path)) return *error;
  const std::optional<std::vector<uint8_t>> bytes = readBytes(path);
  if (!bytes) return readError(path, "cannot open");
  if (auto error = checkStbInput(path, *bytes)) return *error;
  int w = 0, h = 0, channels = 0;
  uint8_t* data = stbi_load_from_memory(bytes->data(), int(bytes->size()), &w, &h, &channels, 4);
  if (!data) return readError(path, stbi_failure_reason() ? stbi_failure_reason() : "decode failed");
  Image8 image = Image8::make(w, h);
  std::copy(data, data + image.rgba.size(), image.rgba.begin());
  stbi_image_free(data);
  return image;
}

Result<ImageF> readExr(const fs::path& path) {
  if (auto error = checkReadable(path)) return *error;
  if (auto error = checkExrDimensions(path)) return *error;
  float* data = nullptr;
  int w = 0, h = 0;
  const char* err = nullptr;
  const int rc = LoadEXR(&data, &w, &h, path.c_str(), &err);
  if (rc != TINYEXR_SUCCESS || !data) {
    std::string reason = err ? err : fmt::format("EXR decoder error {}", rc);
    if (err) FreeEXRErrorMessage(err);
    std::free(data);
    return readError(path, reason);
  }
  ImageF image = ImageF::make(w, h);
  std::copy(data, data + image.rgba.size(), image.rgba.begin());
  std::free(data);  // tinyexr allocates with malloc
  return image;
}

Image8 encodeSrgb8(const ImageF& linear) {
  Image8 out = Image8::make(linear.width, linear.height);
  for (size_t i = 0; i < linear.rgba.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) {
      const float v = linear.rgba[i + c];
      out.rgba[i + c] = quantize(v > 0.0f ? linearToSrgb(std::min(v, 1.0f)) : 0.0f);
    }
    out.rgba[i + 3] = quantize(linear.rgba[i + 3]);
  }
  return out;
}

ImageF decodeSrgb8(const Image8& encoded) {
  const auto& table = srgbDecodeTable();
  ImageF out = ImageF::make(encoded.width, encoded.height);
  for (size_t i = 0; i < encoded.rgba.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) out.rgba[i + c] = table[encoded.rgba[i + c]];
    out.rgba[i + 3] = static_cast<float>(encoded.rgba[i + 3]) / 255.0f;
  }
  return out;
}

Status writeFileAtomically(const fs::path& path, const std::string& contents) {
  return writeAtomically(path, [&](const fs::path& temp, std::string& reason) {
    return writeBytes(temp, std::vector<uint8_t>(contents.begin(), contents.end()), reason);
  });
}

Result<ImageF> readImageLinear(const fs::path& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".png") {
    auto image = readPng(path);
    if (!image) return image.error();
    return decodeSrgb8(*image);
  }
  if (ext == ".exr") return readExr(path);
  if (ext == ".hdr") return readHdr(path);
  return makeError(ExitCode::BadArguments, "{}: unknown image format '{}' (expected .png, .exr or .hdr)", path.string(),
                   ext);
}

Status writeImage(const fs::path& path, const ImageF& linear, ExrPixels exrPixels) {
  const std::string ext = lowerExtension(path);
  if (ext == ".png") return writePng(path, encodeSrgb8(linear));
  if (ext == ".exr") return writeExr(path, linear, exrPixels);
  if (ext == ".hdr") {
    if (linear.empty()) return writeError(path, "image is empty");
    return writeHdr(path, linear);
  }
  return makeError(ExitCode::BadArguments, "{}: unknown image format '{}' (expected .png, .exr or .hdr)", path.string(),
                   ext);
}

}  // namespace rayster
