#pragma once
// The Vulkan instance, the chosen physical device, the logical device, its universal queue and,
// where the device has one, a transfer-only queue for uploads (its copy engine). Also owns the memory allocator, the
// timeline semaphore that orders submissions and the deferred destruction list ("destroyed a frame later").
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <volk.h>

#include "core/error.h"
#include "rhi/pipeline_cache.h"

namespace rayster::rhi {

class MemoryAllocator;

struct Capabilities {
  bool rayTracingPipeline = false;
  bool accelerationStructure = false;
  bool rayQuery = false;
  // vkCmdTraceRaysIndirectKHR (rayTracingPipelineTraceRaysIndirect): launches sized on the GPU, as
  // the specular path's compacted continuation (render/passes/rt_specular.cpp).
  bool traceRaysIndirect = false;
  bool timestamps = false;
  uint32_t shaderGroupHandleSize = 0;
  uint32_t shaderGroupHandleAlignment = 0;
  uint32_t shaderGroupBaseAlignment = 0;
  uint32_t maxRayRecursionDepth = 0;
  uint32_t minScratchOffsetAlignment = 0;
  float timestampPeriodNs = 1.0f;
  bool rayTracing() const { return rayTracingPipeline && accelerationStructure; }
};

// VkPhysicalDeviceIDProperties::deviceUUID: the same physical GPU has the same UUID in every
// process (nvidia-smi -L shows it too), unlike the enumeration index, which a driver may reorder.
using DeviceUuid = std::array<uint8_t, VK_UUID_SIZE>;
// 32 lower-case hex digits with dashes, 8-4-4-4-12.
std::string formatDeviceUuid(const DeviceUuid& uuid);
// The same text (either case; the dashes may be left out); nothing when it is not one.
std::optional<DeviceUuid> parseDeviceUuid(std::string_view text);

struct DeviceInfo {
  VkPhysicalDevice handle = VK_NULL_HANDLE;
  uint32_t index = 0;  // position in vkEnumeratePhysicalDevices' order (rayster info)
  DeviceUuid uuid{};
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  uint32_t apiVersion = 0;
  std::string driverName;
  std::string driverInfo;
  uint64_t deviceLocalBytes = 0;
  Capabilities caps;
  std::string unsuitableReason;  // empty when Rayster can run on it at all
  PipelineCacheKey cacheKey;     // vendor, device and pipelineCacheUUID (rhi/pipeline_cache.h)
  const char* typeName() const;
};

// The queue family for uploads beside the universal one: a family that can transfer but neither
// draw nor compute (a copy engine, which runs while the universal queue builds and renders) and
// copies images of any size (granularity 1×1×1); UINT32_MAX when the device has none.
uint32_t pickTransferFamily(const std::vector<VkQueueFamilyProperties>& families, uint32_t universalFamily);

// Which physical device to use: one by index or UUID, or the best of those whose name contains a
// text (empty: the best of all). The command line's --device is parsed into one by the app.
struct DeviceSelector {
  std::optional<uint32_t> index;
  std::optional<DeviceUuid> uuid;
  std::string nameContains;
  DeviceSelector() = default;
  DeviceSelector(std::string name) : nameContains(std::move(name)) {}  // NOLINT: a name is the common case
  DeviceSelector(const char* name) : nameContains(name) {}             // NOLINT
};

struct ContextOptions {
  bool validation = false;        // Khronos validation layer + synchronization validation
  bool requireRayTracing = true;  // fail with MissingCapability when absent
  DeviceSelector deviceFilter;    // empty: the best device
  bool debugLabels = true;        // pass labels and object names for captures and validation messages
  // Windowed use only (headless needs no surface): the window system's instance extensions and a
  // callback that creates the window's surface; the device then also gets VK_KHR_swapchain and a
  // queue that can present to that surface.
  std::vector<std::string> instanceExtensions;
  std::function<VkResult(VkInstance, VkSurfaceKHR*)> createSurface;
  bool transferQueue = true;  // use a transfer-only queue where there is one (RAYSTER_TRANSFER_QUEUE=0: off)
};

class Context {
 public:
  static Result<std::unique_ptr<Context>> create(const ContextOptions& options);
  // Lists every physical device with its capabilities (for `rayster info`), no logical device.
  static Result<std::vector<DeviceInfo>> listDevices();
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkDevice device() const { return device_; }
  VkPhysicalDevice physicalDevice() const { return info_.handle; }
  VkQueue queue() const { return queue_; }
  VkSurfaceKHR surface() const { return surface_; }  // VK_NULL_HANDLE when headless
  uint32_t queueFamily() const { return queueFamily_; }
  // The transfer-only queue (pickTransferFamily()); UINT32_MAX / VK_NULL_HANDLE when not used.
  bool hasTransferQueue() const { return transferQueue_ != VK_NULL_HANDLE; }
  uint32_t transferFamily() const { return transferFamily_; }
  const DeviceInfo& info() const { return info_; }
  const Capabilities& caps() const { return info_.caps; }
  MemoryAllocator& memory() { return *memory_; }
  // Every pipeline is created through this cache; it is written back to disk when the context
  // is destroyed (rhi/pipeline_cache.h).
  VkPipelineCache pipelineCache() const { return pipelineCache_ ? pipelineCache_->handle() : VK_NULL_HANDLE; }
  const PipelineCache* pipelineCacheState() const { return pipelineCache_.get(); }
  bool validationEnabled() const { return validation_; }
  // Validation messages of error severity seen so far; a test run fails if this is not 0.
  uint32_t validationErrors() const;

  // Submits command buffers on the queue, signalling the timeline; returns the value to wait for.
  uint64_t submit(VkCommandBuffer cmd);
  // The same, also waiting for `wait` (binary, e.g. an acquired swapchain image) before any command
  // and signalling the binary semaphore `signal` (e.g. for presentation).
  uint64_t submit(VkCommandBuffer cmd, VkSemaphore wait, VkSemaphore signal);
  // On the universal queue, its commands waiting for the transfer queue's submission `transferValue`.
  uint64_t submitAfterTransfer(VkCommandBuffer cmd, uint64_t transferValue);
  // On the transfer queue (hasTransferQueue()), signalling its own timeline; returns that value.
  // Whatever such a submission uses is retired after a universal submission that waited for it.
  uint64_t submitTransfer(VkCommandBuffer cmd);
  void wait(uint64_t timelineValue);
  void waitIdle();
  // Runs `destroy` once the GPU has finished every submission made so far.
  void retire(std::function<void()> destroy);
  // Destroys whatever retired objects the GPU no longer uses.
  void collectGarbage();

  // Debug names and labels (no-ops without VK_EXT_debug_utils).
  void setName(VkObjectType type, uint64_t handle, const char* name) const;
  void beginLabel(VkCommandBuffer cmd, const char* name) const;
  void endLabel(VkCommandBuffer cmd) const;

 private:
  Context() = default;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkQueue transferQueue_ = VK_NULL_HANDLE;
  uint32_t transferFamily_ = UINT32_MAX;
  VkSemaphore transferTimeline_ = VK_NULL_HANDLE;
  uint64_t transferSubmitted_ = 0;
  DeviceInfo info_;
  bool validation_ = false;
  bool debugUtils_ = false;
  VkSemaphore timeline_ = VK_NULL_HANDLE;
  uint64_t submitted_ = 0;
  std::vector<std::pair<uint64_t, std::function<void()>>> garbage_;
  std::unique_ptr<MemoryAllocator> memory_;
  std::unique_ptr<PipelineCache> pipelineCache_;
};

}  // namespace rayster::rhi
