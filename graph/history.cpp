#include "graph/history.h"

#include "rhi/context.h"

namespace rayster::graph {

void HistoryStore::beginFrame(uint32_t frame, bool reset) {
  frame_ = frame;
  for (auto& [name, e] : entries_) {
    e.used = false;
    if (reset) e.frames = 0;
  }
}

void HistoryStore::endFrame() {
  for (auto it = entries_.begin(); it != entries_.end();) {
    if (!it->second.used) {
      it = entries_.erase(it);  // rhi::Image defers the destruction until the GPU is done with it
      continue;
    }
    ++it->second.frames;
    ++it;
  }
}

uint32_t HistoryStore::frames(const std::string& name) const {
  auto it = entries_.find(name);
  return it == entries_.end() ? 0u : it->second.frames;
}

uint64_t HistoryStore::bytes() const {
  uint64_t total = 0;
  for (const auto& [name, e] : entries_)
    for (const rhi::Image& image : e.images) total += image ? image.bytes() : 0;
  return total;
}

HistoryStore::Entry& HistoryStore::acquire(rhi::Context& ctx, const std::string& name, const rhi::ImageDesc& desc) {
  Entry& e = entries_[name];
  RAYSTER_ASSERT(!e.used, "a history asked for twice in one frame");
  e.used = true;
  for (int i = 0; i < 2; ++i) {
    if (e.images[i] && e.images[i].desc() == desc) continue;
    e.images[i] = rhi::Image(ctx, desc, (name + "-" + std::to_string(i)).c_str());
    e.states[i] = {};
    e.frames = 0;  // a new image holds no history
  }
  return e;
}

}  // namespace rayster::graph
