#pragma once
// The scene upload's batched forms (render/gpu_scene.cpp): textures and materials recorded into
// the scene's one rhi::UploadBatch instead of a submission each.
#include "render/gpu_scene.h"
#include "rhi/upload.h"

namespace rayster::render {

void uploadMaterials(rhi::Context& ctx, const scene::Scene& scene, GpuScene& gs, rhi::UploadBatch& batch);
rhi::Image uploadTexture(rhi::UploadBatch& batch, const scene::ImageData& image);

}  // namespace rayster::render
