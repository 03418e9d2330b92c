#pragma once
// Instances that move between frames: glTF animation poses and edits (the viewer's selection,
// scripted RenderSettings::moves). Both write the instance table, whose prevWorldFromObject keeps
// last frame's transform so motion vectors and the denoisers' reprojection follow, and the TLAS
// instances, refit before the frame traces.
#include <cstdint>
#include <map>
#include <vector>

#include <glm/glm.hpp>

#include "render/gpu_scene.h"
#include "scene/scene.h"

namespace rayster::rhi {
class Context;
}

namespace rayster::render {

class InstanceMotion {
 public:
  // Starts a run: animated scenes pose from the scene's nodes and animations again.
  void beginRun(rhi::Context& ctx, const scene::Scene& scene, bool animated);
  // Overrides a scene instance's transform from the next frame on (and for later runs). The
  // instance table becomes host-visible on the first edit: waits for the device then, so call it
  // between frames only.
  void set(rhi::Context& ctx, GpuScene& gpu, uint32_t sceneInstance, const glm::mat4& worldFromObject);
  glm::mat4 get(const scene::Scene& scene, uint32_t sceneInstance) const;

  struct Update {
    bool moved = false;        // some instance's transform differs from last frame's
    bool lightsMoved = false;  // a light on an animated node moved (the light table was rewritten)
  };
  // Writes this frame's transforms (animation at `seconds`, then the edits); `first` frames have
  // no motion (prevWorldFromObject = worldFromObject).
  Update update(GpuScene& gpu, bool animated, float seconds, bool first);
  // `camera` (one of scene.cameras) as animated now: where it follows an animated node, the
  // posed copy; else `camera` itself.
  const scene::Camera& camera(const scene::Scene& scene, const scene::Camera& camera, bool animated) const;
  // The scene as animated now (nodes, instances, cameras, lights): the animated copy, else `scene`.
  const scene::Scene& pose(const scene::Scene& scene, bool animated) const { return animated ? pose_ : scene; }
  // Whether the TLAS instances changed since the last refit (and forgets it when `refitting`).
  bool takeTlasRefit(bool refitting);

 private:
  // Lights on animated nodes: this frame's rows into the light table, which becomes host-visible
  // on the first write; whether they differ from last frame's.
  bool writeLights(GpuScene& gpu);

  scene::Scene pose_;  // animated scenes: nodes, instances, animations, cameras and lights only
  rhi::Context* ctx_ = nullptr;
  std::vector<gpu::LightRecord> lightRows_;
  std::map<uint32_t, glm::mat4> overrides_;
  bool dirty_ = false;     // an edit not yet written
  bool settling_ = false;  // written last frame: one more frame brings prevWorldFromObject along
  bool tlasStale_ = false;
};

}  // namespace rayster::render
