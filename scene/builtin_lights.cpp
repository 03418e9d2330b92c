// A light-count scaling scene: the 16-bunny grid of builtin:instances lit by N point lights (no sun)
// on a ring above it, so geometry stays fixed while the light count sweeps 1..kMaxBuiltinLights.
// Up to RenderSettings::shadowLights lights get a shadow layer each; past that the renderer switches
// to one importance-sampled light per pixel (the many-light path), which is what the sweep measures.
#include <cmath>

#include <fmt/format.h>
#include <glm/gtc/constants.hpp>

#include "scene/builtin.h"
#include "scene/builtin_parts.h"

namespace rayster::scene {
namespace {
constexpr uint32_t kLightsSceneInstances = 16;
constexpr float kRingHeight = 2.5f;       // metres above the floor: every bunny sees several lights
constexpr float kLightRadius = 0.05f;     // small soft lights, no visible geometry (triangles stay fixed)
constexpr float kTotalIntensity = 40.0f;  // shared by all lights, so exposure stays put across the sweep
}  // namespace

Result<Scene> makeLightsScene(uint32_t count) {
  if (count == 0 || count > kMaxBuiltinLights)
    return makeError(ExitCode::BadInput, "builtin:lights: count {} is outside 1..{}", count, kMaxBuiltinLights);
  Result<Scene> base = makeInstancesScene(kLightsSceneInstances);
  if (!base) return base.error();
  Scene scene = std::move(*base);
  scene.name = fmt::format("lights:{}", count);
  scene.lights.clear();
  const float ringRadius = 4.0f;
  for (uint32_t i = 0; i < count; ++i) {
    const float a = glm::two_pi<float>() * (float(i) + 0.5f) / float(count);
    // Golden-ratio hues: neighbouring lights differ, so per-light mistakes show.
    const float hue = std::fmod(float(i) * 0.618034f, 1.0f);
    Light l;
    l.name = fmt::format("light-{}", i);
    l.type = LightType::Point;
    l.position = glm::vec3(ringRadius * std::cos(a), kRingHeight + 0.5f * float(i % 3), ringRadius * std::sin(a));
    l.color = glm::vec3(0.6f + 0.4f * std::cos(glm::two_pi<float>() * hue),
                        0.6f + 0.4f * std::cos(glm::two_pi<float>() * (hue - 1.0f / 3.0f)),
                        0.6f + 0.4f * std::cos(glm::two_pi<float>() * (hue - 2.0f / 3.0f)));
    l.intensity = kTotalIntensity / float(count);
    l.radius = kLightRadius;
    scene.lights.push_back(l);
  }
  return scene;
}

}  // namespace rayster::scene
