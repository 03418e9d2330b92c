#pragma once
// Tests only: a device loss or memory exhaustion at a chosen frame of a headless render, to check
// what a scheduler sees (exit code, files kept) without a GPU that fails on cue. The viewer has
// its own (RAYSTER_VIEWER_FAIL_AT, app/viewer/viewer.cpp), in the same format.
#include <cstdint>
#include <optional>

#include <volk.h>

#include "core/error.h"

namespace rayster::app {

struct InjectedFailure {
  VkResult result = VK_SUCCESS;  // VK_ERROR_DEVICE_LOST or VK_ERROR_OUT_OF_DEVICE_MEMORY
  int64_t frame = 0;             // the output frame of --frames-out (a still is frame 0)
};

inline constexpr const char* kRenderFailAtVariable = "RAYSTER_RENDER_FAIL_AT";

// RAYSTER_RENDER_FAIL_AT=lost:F or oom:F: frame F's first submission reports that error
// (rhi::failNextSubmit), which ends the run through VK_CHECK as a real one would.
// Unset: nothing; anything else: ExitCode::BadArguments naming the variable.
Result<std::optional<InjectedFailure>> parseInjectedFailure(const char* value);
Result<std::optional<InjectedFailure>> injectedRenderFailure();  // from the environment

}  // namespace rayster::app
