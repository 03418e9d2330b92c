#include "app/viewer/shader_reload.h"

#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string_view>

#include "shaders/embedded.h"

namespace rayster::app {
namespace fs = std::filesystem;
namespace {

constexpr auto kPollInterval = std::chrono::seconds(1);  // cheap enough, quick enough for an edit loop

// "tonemap.comp.glsl" → "tonemap.comp"; empty for an include (no stage in the name).
std::string shaderName(const fs::path& file) {
  if (file.extension() != ".glsl") return {};
  const std::string stem = file.stem().string();
  return stem.find('.') == std::string::npos ? std::string() : stem;
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

ShaderReloader::ShaderReloader(fs::path glslc, fs::path shaderDir)
    : glslc_(std::move(glslc)), dir_(std::move(shaderDir)), times_(scan()) {}

std::map<fs::path, fs::file_time_type> ShaderReloader::scan() const {
  std::map<fs::path, fs::file_time_type> times;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir_, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const fs::path& p = it->path();
    if (it->is_regular_file(ec) && (p.extension() == ".glsl" || p.extension() == ".h"))
      times[p] = fs::last_write_time(p, ec);
  }
  return times;
}

ShaderReloadResult ShaderReloader::poll(bool force) {
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - lastPoll_ < kPollInterval) return {};
  lastPoll_ = now;
  auto times = scan();
  std::vector<fs::path> changed;
  bool includeChanged = false;
  for (const auto& [path, time] : times) {
    const auto old = times_.find(path);
    if (old != times_.end() && old->second == time) continue;
    if (shaderName(path).empty())
      includeChanged = true;
    else
      changed.push_back(path);
  }
  times_ = std::move(times);
  if (includeChanged) {
    changed.clear();
    for (const auto& [path, time] : times_)
      if (path.parent_path() == dir_ && !shaderName(path).empty()) changed.push_back(path);
  }
  ShaderReloadResult result;
  for (const fs::path& p : changed) {
    ShaderReloadResult one = compile(p);
    result.reloaded.insert(result.reloaded.end(), one.reloaded.begin(), one.reloaded.end());
    if (result.error.empty()) result.error = one.error;
  }
  return result;
}

std::vector<ShaderVariant> shaderVariants(const fs::path& source) {
  std::vector<ShaderVariant> variants;
  std::ifstream in(source);
  constexpr std::string_view kTag = "// variant:";
  for (std::string line; std::getline(in, line);) {
    const size_t at = line.find_first_not_of(" \t");
    if (at == std::string::npos || line.compare(at, kTag.size(), kTag) != 0) continue;
    std::istringstream words(line.substr(at + kTag.size()));
    ShaderVariant v;
    if (!(words >> v.key)) continue;
    for (std::string d; words >> d;) v.defines.push_back(d);
    variants.push_back(std::move(v));
  }
  return variants;
}

ShaderReloadResult ShaderReloader::compile(const fs::path& source) {
  ShaderReloadResult result = compileAs(source, shaderName(source), {});
  if (!result.error.empty()) return result;
  for (const ShaderVariant& v : shaderVariants(source)) {
    ShaderReloadResult one = compileAs(source, v.key, v.defines);
    result.reloaded.insert(result.reloaded.end(), one.reloaded.begin(), one.reloaded.end());
    if (!one.error.empty()) {
      result.error = one.error;
      break;
    }
  }
  return result;
}

ShaderReloadResult ShaderReloader::compileAs(const fs::path& source, const std::string& name,
                                             const std::vector<std::string>& defines) {
  ShaderReloadResult result;
  const std::string stage = name.substr(name.rfind('.') + 1);
  const fs::path out = fs::temp_directory_path() / ("rayster-reload-" + std::to_string(getpid()) + "-" + name + ".spv");
  // The flags of cmake/shaders.cmake; includes resolve against the source tree's shaders/.
  std::string flags;
  for (const std::string& d : defines) flags += " " + quote("-D" + d);
  const std::string cmd = quote(glslc_.string()) + " -fshader-stage=" + stage + " --target-env=vulkan1.3 -O -g" +
                          flags + " -I " + quote(dir_.string()) + " -o " + quote(out.string()) + " " +
                          quote(source.string()) + " 2>&1";
  std::string output;
  if (FILE* pipe = popen(cmd.c_str(), "r")) {
    char buf[4096];
    while (size_t n = fread(buf, 1, sizeof buf, pipe)) output.append(buf, n);
    const int status = pclose(pipe);
    if (status != 0) {
      result.error = output.empty() ? "glslc failed on " + source.string() : output;
      fs::remove(out);
      return result;
    }
  } else {
    result.error = "cannot run " + glslc_.string();
    return result;
  }
  std::ifstream in(out, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  fs::remove(out);
  if (bytes.empty() || bytes.size() % 4 != 0) {
    result.error = "glslc wrote no SPIR-V for " + source.string();
    return result;
  }
  std::vector<uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), bytes.size());
  shaders::setOverride(name, std::move(words));
  result.reloaded.push_back(name);
  return result;
}

}  // namespace rayster::app
