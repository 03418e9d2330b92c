#pragma once
// Image files in and out. Writes are atomic (temp file + rename) so a crashed or failed render
// never leaves a truncated image that a later `rayster compare` would mistake for a result.
#include <filesystem>
#include <string>

#include "core/error.h"
#include "core/image.h"

namespace rayster {

// Exact piecewise sRGB transfer functions (IEC 61966-2-1), not the 2.2 gamma approximation:
// golden images are compared at +-1/255, where the approximation is visibly off near black.
float srgbToLinear(float encoded);
float linearToSrgb(float linear);

// Failures: ExitCode::OutputFailed, "cannot write <path>: <reason>". Creates the parent folder
// if it is missing (users pass -o out/frame.png).
Status writePng(const std::filesystem::path& path, const Image8& image);

// EXR channel type. Half is the default (half the bytes; what compositors and viewers expect of a
// beauty pass); Float keeps values past half's range, e.g. a path-traced view of the sun.
enum class ExrPixels { Half, Float };

// RGBA. Only finite values are written (docs/techniques.md §19: no output holds inf or NaN): values beyond
// the channel type's range are clamped to its largest finite value (65504 for half) and NaN
// becomes 0, with one warning per file saying how many values changed.
Status writeExr(const std::filesystem::path& path, const ImageF& image, ExrPixels pixels = ExrPixels::Half);

// Any file (JSON reports): same atomic temp-and-rename and failure message as the images.
Status writeFileAtomically(const std::filesystem::path& path, const std::string& contents);

// What in an encoded image would make Debian's stb_image 2.27 misbehave, or an empty string: a JPEG
// Huffman table of more than 256 codes overflows its fixed tables (found by fuzz/fuzz_image.cpp).
// Every stb decode of untrusted bytes asks this first.
std::string stbDecodeHazard(const uint8_t* data, size_t size);

// Failures: ExitCode::BadInput, naming the file and the cause.
Result<Image8> readPng(const std::filesystem::path& path);
Result<ImageF> readExr(const std::filesystem::path& path);

// By extension (case-insensitive): .png (sRGB <-> linear, alpha kept linear), .exr, .hdr.
// Unknown extension: ExitCode::BadArguments.
Result<ImageF> readImageLinear(const std::filesystem::path& path);
Status writeImage(const std::filesystem::path& path, const ImageF& linear, ExrPixels exrPixels = ExrPixels::Half);

// Linear float -> 8-bit sRGB with clamping; NaN becomes 0 so one bad pixel cannot poison a PNG.
Image8 encodeSrgb8(const ImageF& linear);
ImageF decodeSrgb8(const Image8& encoded);

}  // namespace rayster
