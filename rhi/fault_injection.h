#pragma once
// Tests only (RAYSTER_RENDER_FAIL_AT, app/fault_injection.h): the next Context::submit() reports
// `result` instead of submitting, and fails through VK_CHECK as a real device loss or memory
// exhaustion would (rhi/vk_check.h: the fatal hook, then the documented exit code).
#include <volk.h>

namespace rayster::rhi {
void failNextSubmit(VkResult result);
}  // namespace rayster::rhi
