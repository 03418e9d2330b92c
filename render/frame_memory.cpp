#include "render/frame_memory.h"

namespace rayster::render {

void setFrameMemory(RenderOutput::SceneStats& st, const graph::FrameMemoryReport& r) {
  st.transientBytes = r.transientBytes;
  st.transientUnaliasedBytes = r.transientUnaliasedBytes;
  st.historyBytes = r.importedBytes;
  st.frameBytes = r.frameBytes();
  st.frameMemoryReport = graph::formatMemoryReport(r);
}

}  // namespace rayster::render
