#include "app/device_option.h"

#include <algorithm>
#include <cctype>

namespace rayster::app {

rhi::DeviceSelector deviceSelector(const std::string& text) {
  rhi::DeviceSelector s;
  const bool digits = !text.empty() && text.size() <= 9 && std::all_of(text.begin(), text.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c));
  });
  if (digits) {
    s.index = uint32_t(std::stoul(text));
  } else if (auto uuid = rhi::parseDeviceUuid(text)) {
    s.uuid = *uuid;
  } else {
    s.nameContains = text;
  }
  return s;
}

}  // namespace rayster::app
