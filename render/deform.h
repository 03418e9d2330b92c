#pragma once
// Skinned and morphed meshes on the GPU (docs/techniques.md §5b). Every instance whose mesh deforms
// (scene::deforms) gets vertex buffers of its own, written each frame by the "deform" compute pass
// from the mesh's rest vertices, its skin's joint matrices and its morph weights, plus last frame's
// positions for the motion vectors (GeometryRecord::prevPositionAddress). Its geometry rows point at
// those buffers, so every pass — raster, traced and the path tracer — sees the pose; on devices
// with ray tracing it has a BLAS of its own, refitted after each deformation and rebuilt when the
// refit's boxes have grown loose: when refitDrift() since the last build passes kRefitDriftLimit
// of the mesh's size (and at the first frame of a run). Each deforming draw's culling box is
// rewritten with the pose (deformedBounds()), so deforming meshes are culled as static ones are.
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "graph/graph.h"
#include "rhi/accel.h"
#include "rhi/resources.h"
#include "scene/scene.h"
#include "shaders/shared/types.h"

namespace rayster::rhi {
class Context;
}

namespace rayster::render {

struct GpuScene;
struct FrameInputs;

// What a deforming mesh's pose is made of: its joint matrices (mesh space) and morph weights.
struct DeformPose {
  std::vector<glm::mat4> joints;
  std::vector<float> weights;
};
// What refitDrift() needs of the mesh: its rest-pose box and each morph target's largest position
// delta.
struct DeformReach {
  glm::vec3 restMin{0.0f}, restMax{0.0f};
  std::vector<float> targetReach;
};
// An upper bound, in the mesh's space, on how far any vertex has moved relative to the rest of the
// mesh between two poses. A refit keeps the built tree and moves its boxes, each growing by at most
// this on every side beyond the rigid motion, so the tree's quality drops as this grows against the
// mesh's size. The skin's share: every joint's motion less the first joint's (a mesh that moves
// only rigidly stays at 0), bounded at the corners of the rest box widened by the morphs (a skinned
// position is an affine, convex blend of its joints'); the morphs': each target's reach × how much
// its weight changed.
float refitDrift(const DeformReach& reach, const DeformPose& built, const DeformPose& now);

// What bounds one deforming primitive in any pose: its rest box, each morph target's per-axis
// range of position deltas, the joints its vertices are weighted to, and whether some vertex has no weight
// (the deform pass leaves it in mesh space).
struct DeformBounds {
  glm::vec3 restMin{0.0f}, restMax{0.0f};
  std::vector<glm::vec3> targetMin, targetMax;  // per target: the smallest and largest delta, per axis
  std::vector<uint32_t> joints;                 // ascending, each once
  bool unweighted = true;
};
DeformBounds deformBounds(const scene::Primitive& primitive, bool skinned);
// A box holding every vertex of the primitive in `pose`, in its instance's object space (a skinned
// instance's is the world): the rest box grown on each axis by each target's delta range × its
// weight (a morphed component is the rest one plus Σ weight × delta), then the union
// of its images under every joint it is weighted to (a skinned position is a convex blend of its
// joints' images of the morphed position), and the widened box itself where a vertex has no weight.
std::pair<glm::vec3, glm::vec3> deformedBounds(const DeformBounds& bounds, const DeformPose& pose);

struct Deformers {
  // A BLAS is rebuilt once refitDrift() since its build passes this share of the mesh's rest-box
  // diagonal: its refitted boxes may then be a tenth of the mesh wider on every side.
  static constexpr float kRefitDriftLimit = 0.1f;

  struct Primitive {
    gpu::DeformPush push{};  // joints and weights addresses set per frame
    rhi::Buffer vertices, previous, influences, targets;
    DeformBounds bounds;
    uint32_t draw = ~0u;  // its GpuScene::draws row, whose DrawRecord box the pose rewrites
  };
  struct Instance {
    uint32_t sceneInstance = 0;
    uint32_t firstGeometry = 0;                  // its GeometryRecord rows
    uint32_t jointOffset = 0, jointCount = 0;    // mat4 rows of `joints`
    uint32_t weightOffset = 0, weightCount = 0;  // float rows of `weights`
    std::vector<Primitive> primitives;
    std::vector<rhi::BlasGeometry> blasGeometries;
    rhi::DynamicBlas blas;  // empty without ray tracing
    DeformReach reach;
    DeformPose built;     // the pose of the last BLAS build
    bool rebuild = true;  // this frame's deformation rebuilds the BLAS (decided with the pose)
  };
  std::vector<Instance> instances;
  rhi::Buffer joints;   // host-visible mat4[], rewritten each frame
  rhi::Buffer weights;  // host-visible float[], rewritten each frame
};

// Called by uploadScene for a scene instance that deforms: its vertex buffers (the rest pose until
// the first deformation) and geometry rows, appended to `rows` after the mesh's own rows, which
// start at `meshFirstGeometry`. Returns the instance's first geometry row.
// `meshBlas`: the mesh's BLAS geometries (opacity and indices carry over).
uint32_t addDeformer(rhi::Context& ctx, const scene::Scene& scene, uint32_t sceneInstance, uint32_t meshFirstGeometry,
                     const std::vector<rhi::BlasGeometry>& meshBlas, std::vector<gpu::GeometryRecord>& rows,
                     GpuScene& gs);
// After every deformer was added: the joint and weight buffers and, with ray tracing, each
// deformer's BLAS (built in the rest pose, so the TLAS can reference it before the first frame).
void finishDeformers(rhi::Context& ctx, GpuScene& gs);

// The frame's "deform" pass: writes the joint matrices and morph weights of `pose` (the scene as
// animated now), deforms every deforming instance, then refits or rebuilds their BLASes. `first`:
// the first frame of a run (no previous positions; BLASes rebuilt). Call before the TLAS update.
void deformMeshes(graph::RenderGraph& graph, const FrameInputs& in, const scene::Scene& scene, const scene::Scene& pose,
                  bool first, bool traced);

}  // namespace rayster::render
