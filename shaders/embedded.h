#pragma once
// SPIR-V compiled from shaders/*.glsl at build time (cmake/shaders.cmake).
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace rayster::shaders {
// Words of the shader compiled from shaders/<name>.glsl, e.g. get("gbuffer.vert"); empty if unknown.
// A runtime override (shader hot reload, app/viewer/shader_reload.h) takes precedence.
std::span<const uint32_t> get(std::string_view name);
// Replaces what get(name) returns from now on (spans returned before for that name dangle: create
// pipelines again after overriding). Not thread-safe: call between frames.
void setOverride(std::string_view name, std::vector<uint32_t> words);
std::span<const uint32_t> overrideOf(std::string_view name);  // empty: none
}  // namespace rayster::shaders
