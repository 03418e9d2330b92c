#pragma once
// Uploads outside the frame (scene loading): pixels into a sampled image, optionally with a full
// mip chain made by linear blits. Barriers here are local to the upload (no graph involved).
#include <cstddef>
#include <span>

#include "rhi/resources.h"

namespace rayster::rhi {

class Context;

// `desc.mips` is ignored: 1, or the full chain when `generateMips`. Ends in SHADER_READ_ONLY_OPTIMAL.
Image uploadImage(Context& ctx, ImageDesc desc, std::span<const std::byte> pixels, bool generateMips, const char* name);

}  // namespace rayster::rhi
