#pragma once
// VK_CHECK is fatal in every build (docs/style.md §7). Device loss and memory exhaustion end the process
// with their documented exit codes (core/error.h) rather than an abort, so scripts can tell them apart.
#include <volk.h>

namespace rayster::rhi {
const char* resultName(VkResult result);
[[noreturn]] void vkFailure(VkResult result, const char* expr, const char* file, int line);
// Called with the one-line cause just before a device loss or memory exhaustion ends the process
// (the viewer shows it in its window); the process still exits with the documented code.
using FatalHook = void (*)(const char* message);
void setFatalHook(FatalHook hook);
}  // namespace rayster::rhi

#define VK_CHECK(expr)                                                                                \
  do {                                                                                                \
    VkResult vk_check_result_ = (expr);                                                               \
    if (vk_check_result_ < 0) ::rayster::rhi::vkFailure(vk_check_result_, #expr, __FILE__, __LINE__); \
  } while (0)
