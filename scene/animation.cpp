#include "scene/animation.h"

#include <algorithm>
#include <cmath>

namespace rayster::scene {
namespace {

glm::quat toQuat(const glm::vec4& xyzw) { return glm::quat(xyzw.w, xyzw.x, xyzw.y, xyzw.z); }
glm::vec4 toXyzw(const glm::quat& q) { return glm::vec4(q.x, q.y, q.z, q.w); }

glm::vec4 normalizedRotation(glm::vec4 q) {
  const float length = glm::length(q);
  return length > 0.0f && std::isfinite(length) ? q / length : glm::vec4(0, 0, 0, 1);
}

// The key value (not a tangent) of key k.
const glm::vec4& keyValue(const AnimationChannel& channel, size_t k) {
  return channel.interp == AnimationChannel::CubicSpline ? channel.values[3 * k + 1] : channel.values[k];
}

// glTF 2.0 Appendix C: Hermite spline with the tangents scaled by the key interval.
glm::vec4 hermite(const AnimationChannel& channel, size_t k, float s, float dt) {
  const glm::vec4& p0 = channel.values[3 * k + 1];
  const glm::vec4 m0 = dt * channel.values[3 * k + 2];  // out-tangent of key k
  const glm::vec4& p1 = channel.values[3 * (k + 1) + 1];
  const glm::vec4 m1 = dt * channel.values[3 * (k + 1) + 0];  // in-tangent of key k + 1
  const float s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1;
}

bool wellFormed(const AnimationChannel& channel, size_t nodeCount) {
  const size_t per = channel.interp == AnimationChannel::CubicSpline ? 3 : 1;
  if (channel.node >= nodeCount || channel.times.empty()) return false;
  if (channel.path == AnimationChannel::Weights)
    return channel.weightCount > 0 && channel.weights.size() == per * channel.times.size() * channel.weightCount;
  return channel.values.size() == per * channel.times.size();
}

glm::vec3 normalizedOr(glm::vec3 v, glm::vec3 fallback) {
  const float length = glm::length(v);
  return length > 0.0f && std::isfinite(length) ? v / length : fallback;
}

}  // namespace

glm::mat4 SceneNode::parentFromNode() const {
  if (hasMatrix) return matrix;
  glm::mat4 m = glm::mat4_cast(rotation);
  m[0] *= scale.x;
  m[1] *= scale.y;
  m[2] *= scale.z;
  m[3] = glm::vec4(translation, 1.0f);
  return m;
}

glm::quat slerpShortest(const glm::quat& a, const glm::quat& b, float t) {
  glm::quat to = b;
  float cosTheta = glm::dot(a, b);
  if (cosTheta < 0.0f) {  // q and -q are the same rotation: take the short way round
    to = -b;
    cosTheta = -cosTheta;
  }
  // Nearly parallel: sin(theta) vanishes, and a normalised lerp is exact to float precision.
  if (cosTheta > 0.9995f)
    return glm::normalize(
        glm::quat(a.w + t * (to.w - a.w), a.x + t * (to.x - a.x), a.y + t * (to.y - a.y), a.z + t * (to.z - a.z)));
  const float theta = std::acos(std::min(cosTheta, 1.0f));
  const float sinTheta = std::sin(theta);
  const float wa = std::sin((1.0f - t) * theta) / sinTheta, wb = std::sin(t * theta) / sinTheta;
  return glm::normalize(
      glm::quat(wa * a.w + wb * to.w, wa * a.x + wb * to.x, wa * a.y + wb * to.y, wa * a.z + wb * to.z));
}

glm::vec4 sampleChannel(const AnimationChannel& channel, float timeSeconds) {
  const std::vector<float>& times = channel.times;
  const bool rotation = channel.path == AnimationChannel::Rotation;
  auto finish = [&](glm::vec4 v) { return rotation ? normalizedRotation(v) : v; };
  if (!(timeSeconds > times.front())) return finish(keyValue(channel, 0));  // also NaN time
  if (timeSeconds >= times.back()) return finish(keyValue(channel, times.size() - 1));
  // times[k] <= t < times[k + 1]
  const size_t k = size_t(std::upper_bound(times.begin(), times.end(), timeSeconds) - times.begin()) - 1;
  const float dt = times[k + 1] - times[k];
  const float s = std::clamp((timeSeconds - times[k]) / dt, 0.0f, 1.0f);
  switch (channel.interp) {
    case AnimationChannel::Step:
      return finish(keyValue(channel, k));
    case AnimationChannel::Linear:
      if (rotation)
        return toXyzw(slerpShortest(toQuat(normalizedRotation(keyValue(channel, k))),
                                    toQuat(normalizedRotation(keyValue(channel, k + 1))), s));
      return glm::mix(keyValue(channel, k), keyValue(channel, k + 1), s);
    case AnimationChannel::CubicSpline:
      return finish(hermite(channel, k, s, dt));
  }
  return finish(keyValue(channel, k));
}

std::vector<float> sampleWeights(const AnimationChannel& channel, float timeSeconds) {
  const std::vector<float>& times = channel.times;
  const size_t n = channel.weightCount;
  const bool cubic = channel.interp == AnimationChannel::CubicSpline;
  // Key k's values (not its tangents): n weights starting here.
  auto key = [&](size_t k) { return channel.weights.data() + (cubic ? (3 * k + 1) * n : k * n); };
  std::vector<float> out(n);
  auto copyKey = [&](size_t k) {
    std::copy(key(k), key(k) + n, out.begin());
    return out;
  };
  if (!(timeSeconds > times.front())) return copyKey(0);
  if (timeSeconds >= times.back()) return copyKey(times.size() - 1);
  const size_t k = size_t(std::upper_bound(times.begin(), times.end(), timeSeconds) - times.begin()) - 1;
  const float dt = times[k + 1] - times[k];
  const float s = std::clamp((timeSeconds - times[k]) / dt, 0.0f, 1.0f);
  switch (channel.interp) {
    case AnimationChannel::Step:
      return copyKey(k);
    case AnimationChannel::Linear:
      for (size_t i = 0; i < n; ++i) out[i] = key(k)[i] + s * (key(k + 1)[i] - key(k)[i]);
      return out;
    case AnimationChannel::CubicSpline: {
      const float* w = channel.weights.data();
      const float s2 = s * s, s3 = s2 * s;
      for (size_t i = 0; i < n; ++i) {
        const float p0 = w[(3 * k + 1) * n + i], m0 = dt * w[(3 * k + 2) * n + i];
        const float p1 = w[(3 * (k + 1) + 1) * n + i], m1 = dt * w[(3 * (k + 1)) * n + i];
        out[i] = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1;
      }
      return out;
    }
  }
  return copyKey(k);
}

void updateWorldTransforms(Scene& scene) {
  for (size_t i = 0; i < scene.nodes.size(); ++i) {
    SceneNode& node = scene.nodes[i];
    const glm::mat4 local = node.parentFromNode();
    // Parents come first; a parent index that breaks that order is treated as a root.
    node.worldFromNode =
        node.parent >= 0 && size_t(node.parent) < i ? scene.nodes[size_t(node.parent)].worldFromNode * local : local;
  }
  for (Instance& instance : scene.instances) {
    if (instance.node < 0 || size_t(instance.node) >= scene.nodes.size()) continue;
    const SceneNode& node = scene.nodes[size_t(instance.node)];
    // A skinned instance is placed by its joints (scene/skinning.h); its own transform is the identity.
    if (instance.skin < 0) instance.worldFromObject = node.worldFromNode;
    if (!node.weights.empty()) instance.morphWeights = node.weights;
  }
  // Cameras and lights on animated nodes: at the node's origin, looking (shining) down its -Z.
  auto nodeWorld = [&](int32_t n) -> const glm::mat4* {
    return n >= 0 && size_t(n) < scene.nodes.size() ? &scene.nodes[size_t(n)].worldFromNode : nullptr;
  };
  for (Camera& camera : scene.cameras)
    if (const glm::mat4* w = nodeWorld(camera.node)) {
      camera.position = glm::vec3((*w)[3]);
      camera.target = camera.position + normalizedOr(glm::mat3(*w) * glm::vec3(0, 0, -1), glm::vec3(0, 0, -1));
      camera.up = normalizedOr(glm::mat3(*w) * glm::vec3(0, 1, 0), glm::vec3(0, 1, 0));
    }
  for (Light& light : scene.lights)
    if (const glm::mat4* w = nodeWorld(light.node)) {
      light.position = glm::vec3((*w)[3]);
      light.direction = normalizedOr(glm::mat3(*w) * glm::vec3(0, 0, -1), light.direction);
    }
}

bool evaluateAnimations(Scene& scene, float timeSeconds, bool loop) {
  if (scene.animations.empty()) return false;
  if (loop) {
    float longest = 0.0f;
    for (const Animation& animation : scene.animations) longest = std::max(longest, animation.duration);
    if (longest > 0.0f && std::isfinite(timeSeconds)) {
      timeSeconds = std::fmod(timeSeconds, longest);
      if (timeSeconds < 0.0f) timeSeconds += longest;
    }
  }
  for (const Animation& animation : scene.animations)
    for (const AnimationChannel& channel : animation.channels) {
      if (!wellFormed(channel, scene.nodes.size())) continue;  // validate() reports these
      SceneNode& node = scene.nodes[channel.node];
      if (channel.path == AnimationChannel::Weights) {
        node.weights = sampleWeights(channel, timeSeconds);
        continue;
      }
      const glm::vec4 v = sampleChannel(channel, timeSeconds);
      switch (channel.path) {
        case AnimationChannel::Translation:
          node.translation = glm::vec3(v);
          break;
        case AnimationChannel::Rotation:
          node.rotation = toQuat(v);
          break;
        case AnimationChannel::Scale:
          node.scale = glm::vec3(v);
          break;
        case AnimationChannel::Weights:
          break;
      }
    }

  std::vector<glm::mat4> before;
  std::vector<std::vector<float>> weightsBefore;
  before.reserve(scene.nodes.size() + scene.instances.size());
  for (const SceneNode& node : scene.nodes) before.push_back(node.worldFromNode);
  for (const Instance& instance : scene.instances) before.push_back(instance.worldFromObject);
  for (const Instance& instance : scene.instances) weightsBefore.push_back(instance.morphWeights);
  updateWorldTransforms(scene);
  size_t i = 0;
  bool changed = false;
  for (const SceneNode& node : scene.nodes) changed |= before[i++] != node.worldFromNode;
  for (const Instance& instance : scene.instances) changed |= before[i++] != instance.worldFromObject;
  for (size_t k = 0; k < scene.instances.size(); ++k) changed |= weightsBefore[k] != scene.instances[k].morphWeights;
  return changed;
}

}  // namespace rayster::scene
