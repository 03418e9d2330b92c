#pragma once
// `--device` (render, bench, view): an index as `rayster info` lists it, a device UUID, or a name
// substring. One process renders on one GPU: a farm gives each process its own --device.
#include <string>

#include "rhi/context.h"

namespace rayster::app {

// Digits only: an index; 32 hex digits (dashes optional, 8-4-4-4-12): a UUID; anything else: a
// name substring. Whether it matches a device is known only when the context is created (exit 4
// with the list of devices).
rhi::DeviceSelector deviceSelector(const std::string& text);

}  // namespace rayster::app
