#include "rhi/context.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/log.h"
#include "rhi/fault_injection.h"
#include "rhi/memory.h"
#include "rhi/vk_check.h"

namespace rayster::rhi {
namespace {

std::atomic<uint32_t> gValidationErrors{0};

VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    ++gValidationErrors;
    std::fprintf(stderr, "rayster: validation error: %s\n", data->pMessage);
  } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    std::fprintf(stderr, "rayster: validation warning: %s\n", data->pMessage);
  }
  return VK_FALSE;
}

bool hasExtension(const std::vector<VkExtensionProperties>& exts, const char* name) {
  return std::any_of(exts.begin(), exts.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

std::vector<VkExtensionProperties> deviceExtensions(VkPhysicalDevice pd) {
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, exts.data());
  return exts;
}

// Extensions every Rayster device needs, and the ones ray tracing adds.
constexpr const char* kRayTracingExtensions[] = {
    VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
    VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME,
    VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME,
};

// RAYSTER_DISABLE_RT=1 (for testing) makes every device look as if it had no ray tracing, so the
// raster fallback and --require-rt can be tested on lavapipe.
bool rayTracingDisabledForTesting() {
  const char* v = std::getenv("RAYSTER_DISABLE_RT");
  return v && std::string(v) == "1";
}

DeviceInfo describe(VkPhysicalDevice pd) {
  DeviceInfo info;
  info.handle = pd;
  VkPhysicalDeviceRayTracingPipelinePropertiesKHR rtProps{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_PROPERTIES_KHR};
  VkPhysicalDeviceAccelerationStructurePropertiesKHR asProps{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceIDProperties id{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &driver;
  driver.pNext = &rtProps;
  rtProps.pNext = &asProps;
  asProps.pNext = &id;
  vkGetPhysicalDeviceProperties2(pd, &props);
  std::copy(std::begin(id.deviceUUID), std::end(id.deviceUUID), info.uuid.begin());
  info.name = props.properties.deviceName;
  info.type = props.properties.deviceType;
  info.apiVersion = props.properties.apiVersion;
  info.driverName = driver.driverName;
  info.driverInfo = driver.driverInfo;
  info.cacheKey.vendorId = props.properties.vendorID;
  info.cacheKey.deviceId = props.properties.deviceID;
  std::copy(std::begin(props.properties.pipelineCacheUUID), std::end(props.properties.pipelineCacheUUID),
            info.cacheKey.uuid.begin());

  VkPhysicalDeviceMemoryProperties mem;
  vkGetPhysicalDeviceMemoryProperties(pd, &mem);
  for (uint32_t i = 0; i < mem.memoryHeapCount; ++i)
    if (mem.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) info.deviceLocalBytes += mem.memoryHeaps[i].size;

  auto exts = deviceExtensions(pd);
  Capabilities& c = info.caps;
  c.accelerationStructure = hasExtension(exts, VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME) &&
                            hasExtension(exts, VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME);
  c.rayTracingPipeline = hasExtension(exts, VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME);
  c.rayQuery = hasExtension(exts, VK_KHR_RAY_QUERY_EXTENSION_NAME);
  if (c.rayTracingPipeline) {
    VkPhysicalDeviceRayTracingPipelineFeaturesKHR rtFeatures{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &rtFeatures;
    vkGetPhysicalDeviceFeatures2(pd, &features);
    c.traceRaysIndirect = rtFeatures.rayTracingPipelineTraceRaysIndirect == VK_TRUE;
  }
  c.shaderGroupHandleSize = rtProps.shaderGroupHandleSize;
  c.shaderGroupHandleAlignment = rtProps.shaderGroupHandleAlignment;
  c.shaderGroupBaseAlignment = rtProps.shaderGroupBaseAlignment;
  c.maxRayRecursionDepth = rtProps.maxRayRecursionDepth;
  c.minScratchOffsetAlignment = asProps.minAccelerationStructureScratchOffsetAlignment;
  c.timestampPeriodNs = props.properties.limits.timestampPeriod;
  c.timestamps = props.properties.limits.timestampComputeAndGraphics;
  if (rayTracingDisabledForTesting()) {
    c.accelerationStructure = false;
    c.rayTracingPipeline = false;
    c.rayQuery = false;
    c.traceRaysIndirect = false;
  }

  if (VK_API_VERSION_MINOR(info.apiVersion) < 3 && VK_API_VERSION_MAJOR(info.apiVersion) == 1)
    info.unsuitableReason =
        "supports Vulkan 1." + std::to_string(VK_API_VERSION_MINOR(info.apiVersion)) + ", Rayster needs 1.3";
  else if (!hasExtension(exts, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
    info.unsuitableReason = "lacks VK_KHR_push_descriptor";
  return info;
}

bool canPresent(VkPhysicalDevice pd, uint32_t family, VkSurfaceKHR surface) {
  if (!surface) return true;
  VkBool32 supported = VK_FALSE;
  return vkGetPhysicalDeviceSurfaceSupportKHR(pd, family, surface, &supported) == VK_SUCCESS && supported;
}

int score(const DeviceInfo& d) {
  int s = 0;
  if (d.type == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU) s += 1000;
  if (d.type == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU) s += 500;
  if (d.caps.rayTracing()) s += 2000;
  return s;
}

Result<VkInstance> createInstance(bool validation, bool labels, bool& debugUtils,
                                  const std::vector<std::string>& required = {}) {
  if (volkInitialize() != VK_SUCCESS)
    return makeError(ExitCode::NoDevice, "no Vulkan loader found (libvulkan.so.1); install a Vulkan driver");
  if (volkGetInstanceVersion() < VK_API_VERSION_1_3)
    return makeError(ExitCode::NoDevice, "the Vulkan loader is older than 1.3");

  uint32_t n = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> available(n);
  vkEnumerateInstanceExtensionProperties(nullptr, &n, available.data());
  std::vector<const char*> exts;
  debugUtils = (validation || labels) && hasExtension(available, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (debugUtils) exts.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  for (const std::string& name : required) {
    if (!hasExtension(available, name.c_str()))
      return makeError(ExitCode::NoDevice, "the Vulkan loader lacks {} (needed for a window)", name);
    exts.push_back(name.c_str());
  }

  std::vector<const char*> layers;
  if (validation) {
    uint32_t ln = 0;
    vkEnumerateInstanceLayerProperties(&ln, nullptr);
    std::vector<VkLayerProperties> lp(ln);
    vkEnumerateInstanceLayerProperties(&ln, lp.data());
    bool found = std::any_of(lp.begin(), lp.end(), [](const VkLayerProperties& l) {
      return std::strcmp(l.layerName, "VK_LAYER_KHRONOS_validation") == 0;
    });
    if (!found)
      return makeError(ExitCode::NoDevice,
                       "validation was requested but VK_LAYER_KHRONOS_validation is not installed "
                       "(apt-get install vulkan-validationlayers)");
    layers.push_back("VK_LAYER_KHRONOS_validation");
  }

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "rayster";
  app.pEngineName = "rayster";
  app.apiVersion = VK_API_VERSION_1_3;
  // Synchronization validation checks the graph's barriers; GPU-assisted validation is too slow here.
  VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pNext = validation ? &features : nullptr;
  ci.pApplicationInfo = &app;
  ci.enabledExtensionCount = uint32_t(exts.size());
  ci.ppEnabledExtensionNames = exts.data();
  ci.enabledLayerCount = uint32_t(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  VkInstance instance = VK_NULL_HANDLE;
  VkResult r = vkCreateInstance(&ci, nullptr, &instance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER || r == VK_ERROR_INITIALIZATION_FAILED)
    return makeError(ExitCode::NoDevice, "no Vulkan driver could be loaded ({})", resultName(r));
  if (r != VK_SUCCESS) return makeError(ExitCode::NoDevice, "vkCreateInstance failed: {}", resultName(r));
  volkLoadInstanceOnly(instance);
  return instance;
}

std::vector<DeviceInfo> enumerate(VkInstance instance) {
  uint32_t n = 0;
  vkEnumeratePhysicalDevices(instance, &n, nullptr);
  std::vector<VkPhysicalDevice> pds(n);
  vkEnumeratePhysicalDevices(instance, &n, pds.data());
  std::vector<DeviceInfo> out;
  for (VkPhysicalDevice pd : pds) {
    out.push_back(describe(pd));
    out.back().index = uint32_t(out.size() - 1);
  }
  return out;
}

// "0 llvmpipe (LLVM 19.1.7, 256 bits) 6c6c766d-..., 1 ...": what a failed --device can choose from.
std::string listForError(const std::vector<DeviceInfo>& devices) {
  std::string list;
  for (const DeviceInfo& d : devices)
    list += (list.empty() ? "" : ", ") + std::to_string(d.index) + " " + d.name + " " + formatDeviceUuid(d.uuid);
  return list;
}

bool selects(const DeviceSelector& s, const DeviceInfo& d) {
  if (s.index) return d.index == *s.index;
  if (s.uuid) return d.uuid == *s.uuid;
  return s.nameContains.empty() || d.name.find(s.nameContains) != std::string::npos;
}

std::string describeSelector(const DeviceSelector& s) {
  if (s.index) return "index " + std::to_string(*s.index);
  if (s.uuid) return "UUID " + formatDeviceUuid(*s.uuid);
  return "'" + s.nameContains + "'";
}

}  // namespace

std::string formatDeviceUuid(const DeviceUuid& uuid) {
  std::string text;
  for (size_t i = 0; i < uuid.size(); ++i) {
    if (i == 4 || i == 6 || i == 8 || i == 10) text += '-';
    char hex[3];
    std::snprintf(hex, sizeof hex, "%02x", uuid[i]);
    text += hex;
  }
  return text;
}

std::optional<DeviceUuid> parseDeviceUuid(std::string_view text) {
  std::string digits;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '-' && (digits.size() == 8 || digits.size() == 12 || digits.size() == 16 || digits.size() == 20)) continue;
    if (!std::isxdigit(static_cast<unsigned char>(c))) return std::nullopt;
    digits += c;
  }
  if (digits.size() != 2 * VK_UUID_SIZE) return std::nullopt;
  DeviceUuid uuid{};
  for (size_t i = 0; i < uuid.size(); ++i) uuid[i] = uint8_t(std::stoul(digits.substr(2 * i, 2), nullptr, 16));
  return uuid;
}

const char* DeviceInfo::typeName() const {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "CPU";
    default:
      return "other";
  }
}

Result<std::vector<DeviceInfo>> Context::listDevices() {
  bool debugUtils = false;
  auto instance = createInstance(false, false, debugUtils);
  if (!instance) return instance.error();
  auto devices = enumerate(*instance);
  vkDestroyInstance(*instance, nullptr);
  return devices;
}

Result<std::unique_ptr<Context>> Context::create(const ContextOptions& options) {
  std::unique_ptr<Context> ctx(new Context());
  auto instance = createInstance(options.validation, options.debugLabels, ctx->debugUtils_, options.instanceExtensions);
  if (!instance) return instance.error();
  ctx->instance_ = *instance;
  if (options.createSurface) {
    VkResult sr = options.createSurface(ctx->instance_, &ctx->surface_);
    if (sr != VK_SUCCESS) return makeError(ExitCode::NoDevice, "cannot create a window surface: {}", resultName(sr));
  }
  ctx->validation_ = options.validation;
  if (options.validation && ctx->debugUtils_) {
    VkDebugUtilsMessengerCreateInfoEXT mci{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    mci.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
    mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    mci.pfnUserCallback = debugCallback;
    VK_CHECK(vkCreateDebugUtilsMessengerEXT(ctx->instance_, &mci, nullptr, &ctx->messenger_));
  }

  auto devices = enumerate(ctx->instance_);
  if (devices.empty()) return makeError(ExitCode::NoDevice, "no Vulkan device found (is a Vulkan driver installed?)");
  std::vector<DeviceInfo> candidates;
  std::string rejected;
  const DeviceSelector& want = options.deviceFilter;
  for (auto& d : devices) {
    if (!selects(want, d)) continue;
    if (!d.unsuitableReason.empty()) {
      rejected += (rejected.empty() ? "" : "; ") + d.name + " " + d.unsuitableReason;
      continue;
    }
    candidates.push_back(d);
  }
  if (candidates.empty()) {
    const bool selected = want.index || want.uuid || !want.nameContains.empty();
    if (selected && rejected.empty())
      return makeError(ExitCode::NoDevice, "no Vulkan device has {} (devices: {})", describeSelector(want),
                       listForError(devices));
    return makeError(ExitCode::NoDevice, "no usable Vulkan device: {}", rejected);
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const DeviceInfo& a, const DeviceInfo& b) { return score(a) > score(b); });
  ctx->info_ = candidates.front();
  if (options.requireRayTracing && !ctx->info_.caps.rayTracing())
    return makeError(ExitCode::MissingCapability,
                     "{} has no ray-tracing pipelines (VK_KHR_ray_tracing_pipeline and VK_KHR_acceleration_structure); "
                     "{}",
                     ctx->info_.name,
                     rayTracingDisabledForTesting()
                         ? "RAYSTER_DISABLE_RT=1 hides it"
                         : "on lavapipe install mesa-vulkan-drivers from bookworm-backports");

  // One queue that does graphics, compute and transfer: enough for a frame recorded in order.
  uint32_t qn = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(ctx->info_.handle, &qn, nullptr);
  std::vector<VkQueueFamilyProperties> qf(qn);
  vkGetPhysicalDeviceQueueFamilyProperties(ctx->info_.handle, &qn, qf.data());
  ctx->queueFamily_ = UINT32_MAX;
  for (uint32_t i = 0; i < qn; ++i)
    if ((qf[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (qf[i].queueFlags & VK_QUEUE_COMPUTE_BIT) &&
        canPresent(ctx->info_.handle, i, ctx->surface_)) {
      ctx->queueFamily_ = i;
      break;
    }
  if (ctx->queueFamily_ == UINT32_MAX)
    return makeError(ExitCode::MissingCapability, "{} has no graphics+compute queue", ctx->info_.name);
  if (qf[ctx->queueFamily_].timestampValidBits == 0) ctx->info_.caps.timestamps = false;

  const bool rt = ctx->info_.caps.rayTracing();
  std::vector<const char*> exts = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  if (ctx->surface_) exts.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  if (rt) exts.insert(exts.end(), std::begin(kRayTracingExtensions), std::end(kRayTracingExtensions));

  VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  vkGetPhysicalDeviceFeatures2(ctx->info_.handle, &supported);

  VkPhysicalDeviceRayTracingPipelineFeaturesKHR rtFeatures{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
  rtFeatures.rayTracingPipeline = VK_TRUE;
  rtFeatures.rayTracingPipelineTraceRaysIndirect = ctx->info_.caps.traceRaysIndirect ? VK_TRUE : VK_FALSE;
  VkPhysicalDeviceAccelerationStructureFeaturesKHR asFeatures{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  asFeatures.accelerationStructure = VK_TRUE;
  asFeatures.pNext = &rtFeatures;
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  f13.synchronization2 = VK_TRUE;
  f13.dynamicRendering = VK_TRUE;
  f13.maintenance4 = VK_TRUE;
  f13.pNext = rt ? &asFeatures : nullptr;
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  f12.bufferDeviceAddress = VK_TRUE;
  f12.scalarBlockLayout = VK_TRUE;
  f12.timelineSemaphore = VK_TRUE;
  f12.hostQueryReset = VK_TRUE;
  f12.descriptorIndexing = VK_TRUE;
  f12.runtimeDescriptorArray = VK_TRUE;
  f12.descriptorBindingPartiallyBound = VK_TRUE;
  f12.shaderSampledImageArrayNonUniformIndexing = VK_TRUE;
  f12.drawIndirectCount = VK_TRUE;  // GPU culling: the G-buffer draws what cull.comp counted
  f12.pNext = &f13;
  VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  f11.shaderDrawParameters = VK_TRUE;  // gl_DrawID picks the culled draw's record
  f11.pNext = &f12;
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.features.shaderInt64 = supported.features.shaderInt64;
  features.features.shaderStorageImageExtendedFormats = supported.features.shaderStorageImageExtendedFormats;
  features.features.samplerAnisotropy = supported.features.samplerAnisotropy;
  // gl_PrimitiveID in fragment shaders (the raster G-buffer's geometric normal) needs it.
  features.features.geometryShader = supported.features.geometryShader;
  features.pNext = &f11;
  if (!supported.features.shaderInt64 || !supported.features.geometryShader)
    return makeError(ExitCode::MissingCapability, "{} lacks shaderInt64 or geometryShader", ctx->info_.name);

  float priority = 1.0f;
  VkDeviceQueueCreateInfo qci[2] = {{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO},
                                    {VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO}};
  qci[0].queueFamilyIndex = ctx->queueFamily_;
  qci[0].queueCount = 1;
  qci[0].pQueuePriorities = &priority;
  const char* transferEnv = std::getenv("RAYSTER_TRANSFER_QUEUE");
  const bool transferWanted = options.transferQueue && !(transferEnv && std::strcmp(transferEnv, "0") == 0);
  const uint32_t transferFamily = transferWanted ? pickTransferFamily(qf, ctx->queueFamily_) : UINT32_MAX;
  qci[1] = qci[0];
  qci[1].queueFamilyIndex = transferFamily;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &features;
  dci.queueCreateInfoCount = transferFamily == UINT32_MAX ? 1 : 2;
  dci.pQueueCreateInfos = qci;
  dci.enabledExtensionCount = uint32_t(exts.size());
  dci.ppEnabledExtensionNames = exts.data();
  VkResult r = vkCreateDevice(ctx->info_.handle, &dci, nullptr, &ctx->device_);
  if (r == VK_ERROR_FEATURE_NOT_PRESENT || r == VK_ERROR_EXTENSION_NOT_PRESENT)
    return makeError(ExitCode::MissingCapability, "{}: vkCreateDevice failed with {}", ctx->info_.name, resultName(r));
  VK_CHECK(r);
  volkLoadDevice(ctx->device_);
  vkGetDeviceQueue(ctx->device_, ctx->queueFamily_, 0, &ctx->queue_);

  VkSemaphoreTypeCreateInfo tci{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
  tci.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
  VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  sci.pNext = &tci;
  VK_CHECK(vkCreateSemaphore(ctx->device_, &sci, nullptr, &ctx->timeline_));
  if (transferFamily != UINT32_MAX) {
    ctx->transferFamily_ = transferFamily;
    vkGetDeviceQueue(ctx->device_, transferFamily, 0, &ctx->transferQueue_);
    VK_CHECK(vkCreateSemaphore(ctx->device_, &sci, nullptr, &ctx->transferTimeline_));
    log::debug("uploads: transfer queue family {}", transferFamily);
  }
  ctx->memory_ = std::make_unique<MemoryAllocator>(*ctx);
  ctx->pipelineCache_ = std::make_unique<PipelineCache>(ctx->device_, ctx->info_.cacheKey);
  log::debug("device: {} ({}, {})", ctx->info_.name, ctx->info_.typeName(), ctx->info_.driverInfo);
  return ctx;
}

Context::~Context() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    if (pipelineCache_) pipelineCache_->save();
    pipelineCache_.reset();
    for (auto& [value, destroy] : garbage_) destroy();
    garbage_.clear();
    memory_.reset();
    vkDestroySemaphore(device_, timeline_, nullptr);
    if (transferTimeline_) vkDestroySemaphore(device_, transferTimeline_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
  if (messenger_) vkDestroyDebugUtilsMessengerEXT(instance_, messenger_, nullptr);
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

uint32_t Context::validationErrors() const { return gValidationErrors.load(); }

namespace {
std::atomic<VkResult> gInjectedSubmitFailure{VK_SUCCESS};
// vkQueueSubmit2, or the failure rhi/fault_injection.h injected in its place.
VkResult queueSubmit(VkQueue queue, const VkSubmitInfo2& si) {
  const VkResult injected = gInjectedSubmitFailure.exchange(VK_SUCCESS);
  return injected != VK_SUCCESS ? injected : vkQueueSubmit2(queue, 1, &si, VK_NULL_HANDLE);
}
}  // namespace

void failNextSubmit(VkResult result) { gInjectedSubmitFailure = result; }

uint64_t Context::submit(VkCommandBuffer cmd) { return submit(cmd, VK_NULL_HANDLE, VK_NULL_HANDLE); }

uint64_t Context::submit(VkCommandBuffer cmd, VkSemaphore wait, VkSemaphore signalBinary) {
  VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cbi.commandBuffer = cmd;
  VkSemaphoreSubmitInfo signals[2] = {{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO},
                                      {VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO}};
  signals[0].semaphore = timeline_;
  signals[0].value = ++submitted_;
  signals[0].stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  signals[1].semaphore = signalBinary;
  signals[1].stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkSemaphoreSubmitInfo waitInfo{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  waitInfo.semaphore = wait;
  waitInfo.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  si.commandBufferInfoCount = 1;
  si.pCommandBufferInfos = &cbi;
  si.signalSemaphoreInfoCount = signalBinary ? 2 : 1;
  si.pSignalSemaphoreInfos = signals;
  si.waitSemaphoreInfoCount = wait ? 1 : 0;
  si.pWaitSemaphoreInfos = &waitInfo;
  VK_CHECK(queueSubmit(queue_, si));
  return submitted_;
}

uint64_t Context::submitAfterTransfer(VkCommandBuffer cmd, uint64_t transferValue) {
  VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cbi.commandBuffer = cmd;
  VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal.semaphore = timeline_;
  signal.value = ++submitted_;
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkSemaphoreSubmitInfo waitInfo{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  waitInfo.semaphore = transferTimeline_;
  waitInfo.value = transferValue;
  waitInfo.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  si.commandBufferInfoCount = 1;
  si.pCommandBufferInfos = &cbi;
  si.signalSemaphoreInfoCount = 1;
  si.pSignalSemaphoreInfos = &signal;
  si.waitSemaphoreInfoCount = transferTimeline_ && transferValue ? 1 : 0;
  si.pWaitSemaphoreInfos = &waitInfo;
  VK_CHECK(vkQueueSubmit2(queue_, 1, &si, VK_NULL_HANDLE));
  return submitted_;
}

uint64_t Context::submitTransfer(VkCommandBuffer cmd) {
  VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cbi.commandBuffer = cmd;
  VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal.semaphore = transferTimeline_;
  signal.value = ++transferSubmitted_;
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  si.commandBufferInfoCount = 1;
  si.pCommandBufferInfos = &cbi;
  si.signalSemaphoreInfoCount = 1;
  si.pSignalSemaphoreInfos = &signal;
  VK_CHECK(vkQueueSubmit2(transferQueue_, 1, &si, VK_NULL_HANDLE));
  return transferSubmitted_;
}

uint32_t pickTransferFamily(const std::vector<VkQueueFamilyProperties>& families, uint32_t universalFamily) {
  for (uint32_t i = 0; i < families.size(); ++i) {
    const VkQueueFamilyProperties& f = families[i];
    const VkExtent3D g = f.minImageTransferGranularity;
    if (i != universalFamily && f.queueCount > 0 && (f.queueFlags & VK_QUEUE_TRANSFER_BIT) &&
        !(f.queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) && g.width == 1 && g.height == 1 &&
        g.depth == 1)
      return i;
  }
  return UINT32_MAX;
}

void Context::wait(uint64_t value) {
  VkSemaphoreWaitInfo wi{VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO};
  wi.semaphoreCount = 1;
  wi.pSemaphores = &timeline_;
  wi.pValues = &value;
  VK_CHECK(vkWaitSemaphores(device_, &wi, UINT64_MAX));
}

void Context::waitIdle() { VK_CHECK(vkDeviceWaitIdle(device_)); }

void Context::retire(std::function<void()> destroy) { garbage_.emplace_back(submitted_, std::move(destroy)); }

void Context::collectGarbage() {
  uint64_t done = 0;
  VK_CHECK(vkGetSemaphoreCounterValue(device_, timeline_, &done));
  auto keep = std::stable_partition(garbage_.begin(), garbage_.end(), [done](const auto& g) { return g.first > done; });
  for (auto it = keep; it != garbage_.end(); ++it) it->second();
  garbage_.erase(keep, garbage_.end());
}

void Context::setName(VkObjectType type, uint64_t handle, const char* name) const {
  if (!debugUtils_ || !vkSetDebugUtilsObjectNameEXT) return;
  VkDebugUtilsObjectNameInfoEXT ni{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  ni.objectType = type;
  ni.objectHandle = handle;
  ni.pObjectName = name;
  vkSetDebugUtilsObjectNameEXT(device_, &ni);
}

void Context::beginLabel(VkCommandBuffer cmd, const char* name) const {
  if (!debugUtils_ || !vkCmdBeginDebugUtilsLabelEXT) return;
  VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
  label.pLabelName = name;
  vkCmdBeginDebugUtilsLabelEXT(cmd, &label);
}

void Context::endLabel(VkCommandBuffer cmd) const {
  if (!debugUtils_ || !vkCmdEndDebugUtilsLabelEXT) return;
  vkCmdEndDebugUtilsLabelEXT(cmd);
}

}  // namespace rayster::rhi
