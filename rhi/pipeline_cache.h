#pragma once
// A VkPipelineCache kept on disk per device (docs/techniques.md §25), so a second run skips most of the
// driver's shader compilation (on the H200 a process's start-up went from 5.6 s to 1.2 s with a warm
// cache). The file is checked before use: a short, corrupt or foreign file (another vendor, device
// or driver: pipelineCacheUUID) is ignored and replaced, never handed to the driver.
//
// Where: $RAYSTER_CACHE_DIR, else $XDG_CACHE_HOME/rayster, else $HOME/.cache/rayster; one file per
// device, named by its pipelineCacheUUID. RAYSTER_CACHE_DIR=off (or an empty value) turns it off.
#include <array>
#include <cstdint>
#include <filesystem>
#include <span>

#include <volk.h>

namespace rayster::rhi {

// What identifies a device's cache: VkPhysicalDeviceProperties' vendorID, deviceID and
// pipelineCacheUUID (the driver changes the UUID when its cache format or compiler changes).
struct PipelineCacheKey {
  uint32_t vendorId = 0, deviceId = 0;
  std::array<uint8_t, VK_UUID_SIZE> uuid{};
};

// Whether `data` starts with a complete version-one pipeline cache header naming this device: the
// header's size field at least 16 + VK_UUID_SIZE and within the data, version
// VK_PIPELINE_CACHE_HEADER_VERSION_ONE, and the key's vendor, device and UUID.
bool pipelineCacheUsable(std::span<const uint8_t> data, const PipelineCacheKey& key);

// The cache file for `key` (see above); empty when caching is off or no folder is known.
std::filesystem::path pipelineCachePath(const PipelineCacheKey& key);

class PipelineCache {
 public:
  PipelineCache() = default;
  // Creates the device's cache, seeded from its file when that file is usable.
  PipelineCache(VkDevice device, const PipelineCacheKey& key);
  ~PipelineCache();
  PipelineCache(const PipelineCache&) = delete;
  PipelineCache& operator=(const PipelineCache&) = delete;

  VkPipelineCache handle() const { return cache_; }
  size_t loadedBytes() const { return loadedBytes_; }  // 0: started empty
  const std::filesystem::path& path() const { return path_; }
  // Writes the cache's current contents (a temporary file renamed over the old one, so concurrent
  // processes never see half a file). Failures are logged at debug level: a cache is optional.
  void save() const;

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  VkPipelineCache cache_ = VK_NULL_HANDLE;
  std::filesystem::path path_;
  size_t loadedBytes_ = 0;
};

}  // namespace rayster::rhi
