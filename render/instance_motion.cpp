#include "render/instance_motion.h"

#include <cstring>

#include <glm/gtc/matrix_inverse.hpp>

#include "rhi/context.h"
#include "scene/animation.h"

namespace rayster::render {

void InstanceMotion::beginRun(rhi::Context& ctx, const scene::Scene& scene, bool animated) {
  ctx_ = &ctx;
  if (animated) {
    pose_.nodes = scene.nodes;
    pose_.instances = scene.instances;
    pose_.animations = scene.animations;
    pose_.cameras = scene.cameras;
    pose_.lights = scene.lights;
  }
  dirty_ = dirty_ || !overrides_.empty();
}

void InstanceMotion::set(rhi::Context& ctx, GpuScene& gpu, uint32_t sceneInstance, const glm::mat4& worldFromObject) {
  if (sceneInstance >= gpu.instanceRowOf.size() || gpu.instanceRowOf[sceneInstance] < 0) return;
  if (!gpu.instances.mapped()) {
    // Static scenes upload the table to device memory; edits rewrite it from the host each frame.
    ctx.waitIdle();
    const size_t bytes = gpu.instanceRecords.size() * sizeof(gpu::InstanceRecord);
    gpu.instances = rhi::Buffer(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, rhi::MemoryUsage::Upload, "instances");
    std::memcpy(gpu.instances.mapped(), gpu.instanceRecords.data(), bytes);
  }
  gpu.instancesDynamic = true;
  overrides_[sceneInstance] = worldFromObject;
  dirty_ = true;
}

const scene::Camera& InstanceMotion::camera(const scene::Scene& scene, const scene::Camera& camera,
                                            bool animated) const {
  const ptrdiff_t i = &camera - scene.cameras.data();
  if (!animated || camera.node < 0 || i < 0 || size_t(i) >= scene.cameras.size() || size_t(i) >= pose_.cameras.size())
    return camera;
  return pose_.cameras[size_t(i)];
}

glm::mat4 InstanceMotion::get(const scene::Scene& scene, uint32_t sceneInstance) const {
  if (auto it = overrides_.find(sceneInstance); it != overrides_.end()) return it->second;
  if (sceneInstance < pose_.instances.size()) return pose_.instances[sceneInstance].worldFromObject;
  return sceneInstance < scene.instances.size() ? scene.instances[sceneInstance].worldFromObject : glm::mat4(1.0f);
}

bool InstanceMotion::writeLights(GpuScene& gpu) {
  bool follows = false;
  for (const scene::Light& l : pose_.lights) follows = follows || l.node >= 0;
  if (!follows || pose_.lights.size() != gpu.lightCount || !ctx_) return false;
  std::vector<gpu::LightRecord> rows;
  for (const scene::Light& l : pose_.lights) rows.push_back(toRecord(l));
  const size_t bytes = rows.size() * sizeof(gpu::LightRecord);
  const bool moved = lightRows_.size() != rows.size() || std::memcmp(lightRows_.data(), rows.data(), bytes) != 0;
  lightRows_ = rows;
  if (!moved && gpu.lights.mapped()) return false;
  if (!gpu.lights.mapped()) {
    // Uploaded to device memory like every static table; lights that follow nodes are rewritten
    // from the host each frame, as the instance table is (one frame in flight).
    ctx_->waitIdle();
    gpu.lights = rhi::Buffer(*ctx_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, rhi::MemoryUsage::Upload, "lights");
  }
  std::memcpy(gpu.lights.mapped(), rows.data(), bytes);
  return moved;
}

InstanceMotion::Update InstanceMotion::update(GpuScene& gpu, bool animated, float seconds, bool first) {
  if (animated) scene::evaluateAnimations(pose_, seconds, true);
  if (!animated && !dirty_ && !settling_) return {};
  Update u;
  for (size_t i = 0; i < gpu.instanceRowOf.size(); ++i) {
    const int32_t row = gpu.instanceRowOf[i];
    if (row < 0) continue;
    gpu::InstanceRecord& r = gpu.instanceRecords[size_t(row)];
    const auto edited = overrides_.find(uint32_t(i));
    const glm::mat4 m = edited != overrides_.end() ? edited->second
                        : animated                 ? pose_.instances[i].worldFromObject
                                                   : r.worldFromObject;
    r.prevWorldFromObject = first ? m : r.worldFromObject;
    r.worldFromObject = m;
    r.normalFromObject = glm::inverseTranspose(m);
    u.moved = u.moved || r.prevWorldFromObject != m;
    VkTransformMatrixKHR& t = gpu.tlasInstances[size_t(row)].transform;  // 3x4 row-major
    for (int rr = 0; rr < 3; ++rr)
      for (int c = 0; c < 4; ++c) t.matrix[rr][c] = m[c][rr];
  }
  std::memcpy(gpu.instances.mapped(), gpu.instanceRecords.data(),
              gpu.instanceRecords.size() * sizeof(gpu::InstanceRecord));
  if (animated) u.lightsMoved = writeLights(gpu);
  settling_ = dirty_;
  dirty_ = false;
  tlasStale_ = true;
  return u;
}

bool InstanceMotion::takeTlasRefit(bool refitting) {
  const bool stale = tlasStale_;
  if (refitting) tlasStale_ = false;
  return stale;
}

}  // namespace rayster::render
