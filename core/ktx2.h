#pragma once
// KTX 2.0 textures (glTF's KHR_texture_basisu and image/ktx2): Rayster's own reader. The base mip
// level of a 2D texture is decoded to the RGBA8 every other image becomes (the renderer makes its
// own mips): uncompressed 8-bit formats and BC1/BC3/BC4/BC5/BC7 payloads, raw or zstd-
// supercompressed. Basis Universal payloads (ETC1S/BasisLZ, UASTC) need a transcoder Debian does
// not package and are refused with a message that says so.
#include <cstdint>
#include <span>

#include "core/error.h"
#include "core/image.h"

namespace rayster {

// The file starts with the KTX 2.0 identifier.
bool isKtx2(std::span<const uint8_t> bytes);

// Decodes level 0 of a KTX2 file. Errors are ExitCode::BadInput with a one-line cause that starts
// with "KTX2" (the caller adds which file or image); nothing the file says is trusted, sizes and
// offsets are checked before anything is read or allocated. `maxSide` bounds width and height.
Result<Image8> decodeKtx2(std::span<const uint8_t> bytes, int maxSide);

}  // namespace rayster
