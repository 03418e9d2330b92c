#pragma once
// SPIR-V compiled from shaders/*.glsl at build time (cmake/shaders.cmake).
#include <cstdint>
#include <span>
#include <string_view>

namespace rayster::shaders {
// Words of the shader compiled from shaders/<name>.glsl, e.g. get("gbuffer.vert"); empty if unknown.
std::span<const uint32_t> get(std::string_view name);
} // namespace rayster::shaders
