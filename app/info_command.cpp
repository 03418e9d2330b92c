#include "app/info_command.h"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "app/build_info.h"
#include "rhi/context.h"

namespace rayster::app {
namespace {

int fail(const Error& e) {
  std::fprintf(stderr, "rayster: error: %s\n", e.message.c_str());
  return int(e.code);
}

std::string usable(const rhi::DeviceInfo& d) {
  if (!d.unsuitableReason.empty()) return d.unsuitableReason;
  return d.caps.rayTracing() ? "yes" : "raster mode only (no ray tracing)";
}

nlohmann::json deviceJson(const rhi::DeviceInfo& d) {
  const rhi::Capabilities& c = d.caps;
  return {{"index", d.index},
          {"uuid", rhi::formatDeviceUuid(d.uuid)},
          {"name", d.name},
          {"type", d.typeName()},
          {"vulkan", fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(d.apiVersion), VK_API_VERSION_MINOR(d.apiVersion),
                                 VK_API_VERSION_PATCH(d.apiVersion))},
          {"driver", d.driverName},
          {"driver_info", d.driverInfo},
          {"device_local_bytes", d.deviceLocalBytes},
          {"ray_tracing_pipeline", c.rayTracingPipeline},
          {"acceleration_structure", c.accelerationStructure},
          {"ray_query", c.rayQuery},
          {"usable", d.unsuitableReason.empty()},
          {"usable_by_rayster", usable(d)}};
}

void printDevice(const rhi::DeviceInfo& d) {
  const rhi::Capabilities& c = d.caps;
  std::printf("%u: %s (%s)\n", d.index, d.name.c_str(), d.typeName());
  std::printf("  UUID %s\n", rhi::formatDeviceUuid(d.uuid).c_str());
  std::printf("  Vulkan %u.%u.%u, driver %s %s, %.1f GiB device-local\n", VK_API_VERSION_MAJOR(d.apiVersion),
              VK_API_VERSION_MINOR(d.apiVersion), VK_API_VERSION_PATCH(d.apiVersion), d.driverName.c_str(),
              d.driverInfo.c_str(), double(d.deviceLocalBytes) / (1 << 30));
  std::printf("  ray-tracing pipeline: %s, acceleration structures: %s, ray queries: %s\n",
              c.rayTracingPipeline ? "yes" : "no", c.accelerationStructure ? "yes" : "no", c.rayQuery ? "yes" : "no");
  if (c.rayTracingPipeline)
    std::printf("  shader group handle %u B (alignment %u, base alignment %u), max recursion %u\n",
                c.shaderGroupHandleSize, c.shaderGroupHandleAlignment, c.shaderGroupBaseAlignment,
                c.maxRayRecursionDepth);
  std::printf("  usable by rayster: %s\n", usable(d).c_str());
}

}  // namespace

int infoCommand(bool json) {
  auto devices = rhi::Context::listDevices();
  if (!devices) return fail(devices.error());
  if (devices->empty()) return fail(makeError(ExitCode::NoDevice, "no Vulkan device found"));
  if (json) {
    nlohmann::json list = nlohmann::json::array();
    for (const rhi::DeviceInfo& d : *devices) list.push_back(deviceJson(d));
    std::printf("%s\n", list.dump(2).c_str());
    return 0;
  }
  std::printf("rayster %s (commit %s)\n", buildVersion(), buildCommit());
  for (const rhi::DeviceInfo& d : *devices) printDevice(d);
  return 0;
}

}  // namespace rayster::app
