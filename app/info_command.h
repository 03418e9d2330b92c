#pragma once
// `rayster info`: every Vulkan device with its index and UUID (what --device takes) and capabilities.

namespace rayster::app {

// json: a JSON array on stdout instead of text, one object per device.
int infoCommand(bool json);

}  // namespace rayster::app
