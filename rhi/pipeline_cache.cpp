#include "rhi/pipeline_cache.h"

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

#include "core/log.h"

namespace rayster::rhi {

namespace {

// The version-one header (Vulkan spec, vkGetPipelineCacheData): four 32-bit words then the UUID.
constexpr size_t kHeaderBytes = 16 + VK_UUID_SIZE;

uint32_t word(std::span<const uint8_t> data, size_t index) {
  uint32_t w;
  std::memcpy(&w, data.data() + index * 4, 4);
  return w;
}

std::string hex(std::span<const uint8_t> bytes) {
  static const char* digits = "0123456789abcdef";
  std::string s;
  for (uint8_t b : bytes) {
    s += digits[b >> 4];
    s += digits[b & 15];
  }
  return s;
}

std::filesystem::path cacheFolder() {
  if (const char* dir = std::getenv("RAYSTER_CACHE_DIR")) {
    if (*dir == '\0' || std::strcmp(dir, "off") == 0) return {};
    return dir;
  }
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "rayster";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "rayster";
  return {};
}

}  // namespace

bool pipelineCacheUsable(std::span<const uint8_t> data, const PipelineCacheKey& key) {
  if (data.size() < kHeaderBytes) return false;
  const uint32_t headerSize = word(data, 0);
  if (headerSize < kHeaderBytes || headerSize > data.size()) return false;
  if (word(data, 1) != uint32_t(VK_PIPELINE_CACHE_HEADER_VERSION_ONE)) return false;
  if (word(data, 2) != key.vendorId || word(data, 3) != key.deviceId) return false;
  return std::memcmp(data.data() + 16, key.uuid.data(), VK_UUID_SIZE) == 0;
}

std::filesystem::path pipelineCachePath(const PipelineCacheKey& key) {
  const std::filesystem::path folder = cacheFolder();
  if (folder.empty()) return {};
  return folder / ("pipelines-" + hex(key.uuid) + ".bin");
}

PipelineCache::PipelineCache(VkDevice device, const PipelineCacheKey& key)
    : device_(device), path_(pipelineCachePath(key)) {
  std::vector<uint8_t> data;
  if (!path_.empty()) {
    std::ifstream in(path_, std::ios::binary);
    if (in) data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (!data.empty() && !pipelineCacheUsable(data, key)) {
      log::debug("pipeline cache {}: not for this device or damaged, starting empty", path_.string());
      data.clear();
    }
  }
  VkPipelineCacheCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  ci.initialDataSize = data.size();
  ci.pInitialData = data.empty() ? nullptr : data.data();
  if (vkCreatePipelineCache(device_, &ci, nullptr, &cache_) != VK_SUCCESS) {
    // A driver that rejects the data anyway: start empty; without any cache, pipelines still build.
    ci.initialDataSize = 0;
    ci.pInitialData = nullptr;
    data.clear();
    if (vkCreatePipelineCache(device_, &ci, nullptr, &cache_) != VK_SUCCESS) cache_ = VK_NULL_HANDLE;
  }
  loadedBytes_ = data.size();
  if (loadedBytes_) log::debug("pipeline cache {}: {} bytes loaded", path_.string(), loadedBytes_);
}

PipelineCache::~PipelineCache() {
  if (cache_) vkDestroyPipelineCache(device_, cache_, nullptr);
}

void PipelineCache::save() const {
  if (!cache_ || path_.empty()) return;
  size_t size = 0;
  if (vkGetPipelineCacheData(device_, cache_, &size, nullptr) != VK_SUCCESS || size == 0) return;
  std::vector<uint8_t> data(size);
  if (vkGetPipelineCacheData(device_, cache_, &size, data.data()) != VK_SUCCESS) return;
  data.resize(size);
  std::error_code ec;
  std::filesystem::create_directories(path_.parent_path(), ec);
  const std::filesystem::path tmp = path_.string() + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data.data()), std::streamsize(data.size()));
    if (!out) {
      log::debug("pipeline cache {}: could not write", tmp.string());
      std::filesystem::remove(tmp, ec);
      return;
    }
  }
  std::filesystem::rename(tmp, path_, ec);
  if (ec) {
    log::debug("pipeline cache {}: {}", path_.string(), ec.message());
    std::filesystem::remove(tmp, ec);
  }
}

}  // namespace rayster::rhi
