#pragma once
// Shader hot reload (development builds, RAYSTER_SHADER_HOT_RELOAD): polls the modification times
// of shaders/ once per second, recompiles changed NAME.STAGE.glsl files with glslc the way
// cmake/shaders.cmake does (with the variants its `// variant:` lines declare), and installs the
// SPIR-V as shaders::setOverride; the caller then
// recreates the pipelines. A change to an included file (lib/, shared/) recompiles every shader.
// A failed compile installs nothing: the old modules stay, and the compiler's message is returned.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace rayster::app {

struct ShaderReloadResult {
  std::vector<std::string> reloaded;  // shader names (e.g. "tonemap.comp") with new SPIR-V
  std::string error;                  // glslc's output of the first failed compile; empty: none
};

// The `// variant: KEY DEFINE...` lines of a shader source (cmake/shaders.cmake).
struct ShaderVariant {
  std::string key;                   // e.g. "raw_ao.rgen"
  std::vector<std::string> defines;  // NAME or NAME=VALUE
};
std::vector<ShaderVariant> shaderVariants(const std::filesystem::path& source);

class ShaderReloader {
 public:
  ShaderReloader(std::filesystem::path glslc, std::filesystem::path shaderDir);
  // At most once per second (or now, with `force`): compiles what changed since the last poll.
  ShaderReloadResult poll(bool force = false);
  // Compiles one shader source (shaders/NAME.STAGE.glsl) and its variants; on success installs
  // each (the first failure stops, keeping the old modules of what it did not reach).
  ShaderReloadResult compile(const std::filesystem::path& source);

 private:
  ShaderReloadResult compileAs(const std::filesystem::path& source, const std::string& name,
                               const std::vector<std::string>& defines);
  std::map<std::filesystem::path, std::filesystem::file_time_type> scan() const;
  std::filesystem::path glslc_, dir_;
  std::map<std::filesystem::path, std::filesystem::file_time_type> times_;
  std::chrono::steady_clock::time_point lastPoll_{};
};

}  // namespace rayster::app
