#pragma once
// The frame-resources figures of RenderOutput::SceneStats, from the transient pool's report.
#include "graph/transient_pool.h"
#include "render/renderer.h"

namespace rayster::render {

void setFrameMemory(RenderOutput::SceneStats& stats, const graph::FrameMemoryReport& report);

}  // namespace rayster::render
