#include "rhi/vk_check.h"

#include <cstdio>
#include <cstdlib>
#include <utility>

#include "core/error.h"

namespace rayster::rhi {

const char* resultName(VkResult r) {
  switch (r) {
#define RAYSTER_CASE(x) \
  case x:               \
    return #x;
    RAYSTER_CASE(VK_SUCCESS)
    RAYSTER_CASE(VK_NOT_READY)
    RAYSTER_CASE(VK_TIMEOUT)
    RAYSTER_CASE(VK_INCOMPLETE)
    RAYSTER_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    RAYSTER_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    RAYSTER_CASE(VK_ERROR_INITIALIZATION_FAILED)
    RAYSTER_CASE(VK_ERROR_DEVICE_LOST)
    RAYSTER_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    RAYSTER_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    RAYSTER_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    RAYSTER_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    RAYSTER_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    RAYSTER_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    RAYSTER_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    RAYSTER_CASE(VK_ERROR_FRAGMENTED_POOL)
    RAYSTER_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    RAYSTER_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    RAYSTER_CASE(VK_ERROR_FRAGMENTATION)
    RAYSTER_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    RAYSTER_CASE(VK_ERROR_SURFACE_LOST_KHR)
    RAYSTER_CASE(VK_ERROR_OUT_OF_DATE_KHR)
    RAYSTER_CASE(VK_ERROR_VALIDATION_FAILED_EXT)
    RAYSTER_CASE(VK_OPERATION_DEFERRED_KHR)
    RAYSTER_CASE(VK_OPERATION_NOT_DEFERRED_KHR)
#undef RAYSTER_CASE
    default:
      return "VK_ERROR_UNKNOWN";
  }
}

namespace {
FatalHook gFatalHook = nullptr;
}

void setFatalHook(FatalHook hook) { gFatalHook = hook; }

void vkFailure(VkResult r, const char* expr, const char* file, int line) {
  ExitCode code = ExitCode::Failure;
  const char* what = "Vulkan call failed";
  if (r == VK_ERROR_DEVICE_LOST) {
    code = ExitCode::DeviceLost;
    what = "the GPU device was lost";
  } else if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY) {
    code = ExitCode::OutOfMemory;
    what = r == VK_ERROR_OUT_OF_DEVICE_MEMORY ? "out of device memory" : "out of host memory";
  }
  std::fprintf(stderr, "rayster: error: %s: %s returned %s (%s:%d)\n", what, expr, resultName(r), file, line);
  std::fflush(stderr);
  if (code == ExitCode::Failure) std::abort();
  if (FatalHook hook = std::exchange(gFatalHook, nullptr)) hook(what);
  std::_Exit(static_cast<int>(code));
}

}  // namespace rayster::rhi
