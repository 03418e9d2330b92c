// glTF 2.0 animations: samplers read through the bounds-checked accessors, checked as the spec
// requires (keys strictly increasing, one output per key, three per key for CUBICSPLINE), and
// turned into AnimationChannels on Scene::nodes (translation, rotation, scale and morph weights).
#include <algorithm>
#include <cmath>

#include "core/log.h"
#include "scene/gltf_internal.h"

namespace rayster::scene::gltf {
namespace {

bool finite(const glm::vec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

std::string animationLabel(const tinygltf::Animation& animation, size_t index) {
  return animation.name.empty() ? fmt::format("animation {}", index)
                                : fmt::format("animation {} '{}'", index, animation.name);
}

Result<AnimationChannel::Interp> interpolation(const std::string& name, const std::string& where,
                                               const std::string& file) {
  if (name.empty() || name == "LINEAR") return AnimationChannel::Linear;
  if (name == "STEP") return AnimationChannel::Step;
  if (name == "CUBICSPLINE") return AnimationChannel::CubicSpline;
  // The schema allows any string (the validator only warns); LINEAR is the default glTF gives.
  log::warn("{}: {} has interpolation '{}', which glTF 2.0 does not define; interpolated linearly", file, where, name);
  return AnimationChannel::Linear;
}

Result<std::vector<float>> keyTimes(const tinygltf::Model& model, int accessor, const std::string& where,
                                    const std::string& file) {
  Result<std::vector<float>> times = readScalars(model, accessor, file);
  if (!times) return times.error();
  if (times->empty()) return bad(file, "{} has no keyframes", where);
  for (size_t i = 0; i < times->size(); ++i) {
    const float t = (*times)[i];
    if (!std::isfinite(t) || t < 0.0f) return bad(file, "{} key time {} is {}, not a finite time >= 0", where, i, t);
    if (i > 0 && !(t > (*times)[i - 1]))
      return bad(file, "{} key times are not strictly increasing (key {} at {} after {})", where, i, t,
                 (*times)[i - 1]);
  }
  return times;
}

// The sampler's output as vec4s: xyz0 for translation and scale, xyzw for rotation.
Result<std::vector<glm::vec4>> keyValues(const tinygltf::Model& model, int accessor, AnimationChannel::Path path,
                                         const std::string& file) {
  if (path == AnimationChannel::Rotation) return readVec4(model, accessor, file);
  Result<std::vector<glm::vec3>> values = readVec3(model, accessor, file);
  if (!values) return values.error();
  std::vector<glm::vec4> out;
  out.reserve(values->size());
  for (const glm::vec3& v : *values) out.emplace_back(v, 0.0f);
  return out;
}

// A weights channel: `targets` scalars per key (× 3 for CUBICSPLINE), finite.
Status readWeights(const tinygltf::Model& model, int accessor, size_t targets, const std::string& where,
                   const std::string& file, AnimationChannel& channel) {
  Result<std::vector<float>> values = readScalars(model, accessor, file);
  if (!values) return values.error();
  const bool cubic = channel.interp == AnimationChannel::CubicSpline;
  const size_t expected = channel.times.size() * targets * (cubic ? 3 : 1);
  if (values->size() != expected)
    return bad(file, "{} has {} output values for {} keys of {} morph weights (expected {})", where, values->size(),
               channel.times.size(), targets, expected);
  for (size_t i = 0; i < values->size(); ++i)
    if (!std::isfinite((*values)[i])) return bad(file, "{} output value {} is not finite", where, i);
  channel.weights = std::move(*values);
  channel.weightCount = uint32_t(targets);
  return okStatus();
}

Result<AnimationChannel> convertChannel(const tinygltf::Model& model, const tinygltf::Animation& animation,
                                        const tinygltf::AnimationChannel& src, AnimationChannel::Path path,
                                        size_t targets, const std::string& where, const std::string& file) {
  if (src.sampler < 0 || size_t(src.sampler) >= animation.samplers.size())
    return bad(file, "{} uses sampler {}, which does not exist", where, src.sampler);
  const tinygltf::AnimationSampler& sampler = animation.samplers[size_t(src.sampler)];
  AnimationChannel channel;
  channel.path = path;
  Result<AnimationChannel::Interp> interp = interpolation(sampler.interpolation, where, file);
  if (!interp) return interp.error();
  channel.interp = *interp;
  Result<std::vector<float>> times = keyTimes(model, sampler.input, where, file);
  if (!times) return times.error();
  channel.times = std::move(*times);
  if (path == AnimationChannel::Weights) {
    if (channel.interp == AnimationChannel::CubicSpline && channel.times.size() < 2)
      return bad(file, "{} is CUBICSPLINE with fewer than 2 keys", where);
    RAYSTER_TRY(readWeights(model, sampler.output, targets, where, file, channel));
    return channel;
  }
  Result<std::vector<glm::vec4>> values = keyValues(model, sampler.output, path, file);
  if (!values) return values.error();
  channel.values = std::move(*values);

  const bool cubic = channel.interp == AnimationChannel::CubicSpline;
  const size_t expected = channel.times.size() * (cubic ? 3 : 1);
  if (channel.values.size() != expected)
    return bad(file, "{} has {} output values for {} keys (expected {})", where, channel.values.size(),
               channel.times.size(), expected);
  if (cubic && channel.times.size() < 2) return bad(file, "{} is CUBICSPLINE with fewer than 2 keys", where);
  for (size_t i = 0; i < channel.values.size(); ++i) {
    if (!finite(channel.values[i])) return bad(file, "{} output value {} is not finite", where, i);
    // Key values of rotations are unit quaternions (exporters round); tangents are not.
    if (path == AnimationChannel::Rotation && (!cubic || i % 3 == 1)) {
      const float length = glm::length(channel.values[i]);
      if (!(length > 0.0f)) return bad(file, "{} rotation key {} is a zero quaternion", where, cubic ? i / 3 : i);
      channel.values[i] /= length;
    }
  }
  return channel;
}

// Instances, cameras and lights keep their node only if it or one of its parents is animated (an
// instance also if its node's morph weights are). A skinned instance follows its joints, not its
// node.
void markAnimatedInstances(Scene& scene) {
  std::vector<bool> moves(scene.nodes.size(), false), morphs(scene.nodes.size(), false);
  for (const Animation& animation : scene.animations)
    for (const AnimationChannel& channel : animation.channels)
      (channel.path == AnimationChannel::Weights ? morphs : moves)[channel.node] = true;
  for (size_t i = 0; i < scene.nodes.size(); ++i)  // parents come first
    if (scene.nodes[i].parent >= 0 && moves[size_t(scene.nodes[i].parent)]) moves[i] = true;
  for (Instance& instance : scene.instances) {
    if (instance.node < 0) continue;
    const size_t n = size_t(instance.node);
    if (!(moves[n] && instance.skin < 0) && !morphs[n]) instance.node = -1;
  }
  for (Camera& camera : scene.cameras)
    if (camera.node >= 0 && !moves[size_t(camera.node)]) camera.node = -1;
  for (Light& light : scene.lights)
    if (light.node >= 0 && !moves[size_t(light.node)]) light.node = -1;
}

}  // namespace

Status convertAnimations(const tinygltf::Model& model, const std::string& file, const std::vector<int>& sceneNodeOf,
                         Scene& scene) {
  bool warnedPath = false;
  for (size_t a = 0; a < model.animations.size(); ++a) {
    const tinygltf::Animation& src = model.animations[a];
    Animation animation;
    animation.name = src.name.empty() ? fmt::format("animation{}", a) : src.name;
    for (size_t c = 0; c < src.channels.size(); ++c) {
      const tinygltf::AnimationChannel& channel = src.channels[c];
      const std::string where = fmt::format("{} channel {}", animationLabel(src, a), c);
      const std::string& pathName = channel.target_path;
      AnimationChannel::Path path;
      if (pathName == "translation")
        path = AnimationChannel::Translation;
      else if (pathName == "rotation")
        path = AnimationChannel::Rotation;
      else if (pathName == "scale")
        path = AnimationChannel::Scale;
      else if (pathName == "weights")
        path = AnimationChannel::Weights;
      else {
        if (!warnedPath) log::warn("{}: animation path '{}' is not supported; ignored", file, pathName);
        warnedPath = true;
        continue;
      }
      if (channel.target_node < 0) continue;  // no node: the channel animates nothing (glTF 2.0 §5.5)
      if (size_t(channel.target_node) >= model.nodes.size())
        return bad(file, "{} targets node {}, which does not exist", where, channel.target_node);
      size_t targets = 0;  // morph targets of the node's mesh, for a weights channel
      if (path == AnimationChannel::Weights) {
        const tinygltf::Node& target = model.nodes[size_t(channel.target_node)];
        if (target.mesh >= 0 && size_t(target.mesh) < model.meshes.size() &&
            !model.meshes[size_t(target.mesh)].primitives.empty())
          targets = model.meshes[size_t(target.mesh)].primitives.front().targets.size();
        if (targets == 0)
          return bad(file, "{} animates the weights of node {}, whose mesh has no morph targets", where,
                     channel.target_node);
      }
      Result<AnimationChannel> converted = convertChannel(model, src, channel, path, targets, where, file);
      if (!converted) return converted.error();
      const int node = sceneNodeOf[size_t(channel.target_node)];
      if (node < 0) continue;  // a node outside the displayed scene
      if (path != AnimationChannel::Weights && scene.nodes[size_t(node)].hasMatrix)
        return bad(file, "{} targets node {}, which has a matrix (glTF allows animating only TRS)", where,
                   channel.target_node);
      converted->node = uint32_t(node);
      animation.duration = std::max(animation.duration, converted->times.back());
      animation.channels.push_back(std::move(*converted));
    }
    if (!animation.channels.empty()) scene.animations.push_back(std::move(animation));
  }
  markAnimatedInstances(scene);
  return okStatus();
}

}  // namespace rayster::scene::gltf
