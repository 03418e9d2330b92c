#include "graph/transient_pool.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include <fmt/format.h>

#include "core/log.h"
#include "rhi/context.h"

namespace rayster::graph {

const char* formatName(VkFormat f) {
  switch (f) {
    case VK_FORMAT_R8G8B8A8_UNORM:
      return "RGBA8";
    case VK_FORMAT_R8G8B8A8_SRGB:
      return "RGBA8_SRGB";
    case VK_FORMAT_B8G8R8A8_UNORM:
      return "BGRA8";
    case VK_FORMAT_R16_SFLOAT:
      return "R16F";
    case VK_FORMAT_R16G16_SFLOAT:
      return "RG16F";
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      return "RGBA16F";
    case VK_FORMAT_R16G16B16A16_SNORM:
      return "RGBA16_SNORM";
    case VK_FORMAT_R32_SFLOAT:
      return "R32F";
    case VK_FORMAT_R32_UINT:
      return "R32UI";
    case VK_FORMAT_R32G32_SFLOAT:
      return "RG32F";
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return "RGBA32F";
    case VK_FORMAT_R32G32B32A32_UINT:
      return "RGBA32UI";
    case VK_FORMAT_D32_SFLOAT:
      return "D32F";
    case VK_FORMAT_D16_UNORM:
      return "D16";
    case VK_FORMAT_D24_UNORM_S8_UINT:
      return "D24S8";
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
      return "D32FS8";
    default:
      return "other";
  }
}

std::string formatMemoryReport(const FrameMemoryReport& r) {
  auto mib = [](uint64_t b) { return double(b) / (1 << 20); };
  std::string s = fmt::format(
      "frame resources: {:.1f} MiB = transients {:.1f} MiB (aliased; {:.1f} MiB unaliased) + "
      "imported {:.1f} MiB\n",
      mib(r.frameBytes()), mib(r.transientBytes), mib(r.transientUnaliasedBytes), mib(r.importedBytes));
  s += fmt::format("  {:<28} {:<13} {:>11} {:>9}  {}\n", "image", "format", "size", "MiB", "placement / lifetime");
  for (const FrameMemoryEntry& e : r.entries) {
    const std::string size = e.desc.layers > 1 ? fmt::format("{}x{}x{}", e.desc.width, e.desc.height, e.desc.layers)
                                               : fmt::format("{}x{}", e.desc.width, e.desc.height);
    const std::string where =
        e.imported ? std::string("imported (history/output)")
                   : fmt::format("heap {} +{:.1f} MiB, {} .. {}", e.heap, mib(e.offset), e.firstPass, e.lastPass);
    s += fmt::format("  {:<28} {:<13} {:>11} {:>9.2f}  {}\n", e.name, formatName(e.desc.format), size, mib(e.bytes),
                     where);
  }
  return s;
}

bool TransientPool::aliasingDefault() {
  const char* v = std::getenv("RAYSTER_NO_ALIASING");
  return !(v && *v && std::strcmp(v, "0") != 0);
}

TransientPool& TransientPool::operator=(TransientPool&& o) noexcept {
  if (this == &o) return *this;
  release();
  aliasing_ = o.aliasing_;
  ctx_ = o.ctx_;
  requests_ = std::move(o.requests_);
  items_ = std::move(o.items_);
  plan_ = std::move(o.plan_);
  heaps_ = std::move(o.heaps_);
  images_ = std::move(o.images_);
  imported_ = std::move(o.imported_);
  rebuilds_ = o.rebuilds_;
  o.heaps_.clear();
  o.images_.clear();
  o.requests_.clear();
  o.items_.clear();
  o.plan_ = {};
  o.imported_.clear();
  return *this;
}

void TransientPool::release() {
  images_.clear();  // retired before the heaps below them (Context::retire runs in order)
  for (const rhi::Allocation& a : heaps_) ctx_->retire([ctx = ctx_, a] { ctx->memory().free(a); });
  heaps_.clear();
  plan_ = {};
  items_.clear();
  requests_.clear();
}

std::vector<const rhi::Image*> TransientPool::acquire(rhi::Context& ctx, const std::vector<TransientRequest>& requests,
                                                      std::vector<std::vector<uint32_t>>& before) {
  std::vector<AliasItem> items(requests.size());
  bool reuse = ctx_ == &ctx && requests.size() == requests_.size();
  for (size_t i = 0; reuse && i < requests.size(); ++i)
    reuse = requests[i].name == requests_[i].name && requests[i].desc == requests_[i].desc;
  auto lifetimes = [&](std::vector<AliasItem>& it) {
    for (size_t i = 0; i < requests.size(); ++i) {
      // Without aliasing every image lives through the whole frame, so none share memory.
      it[i].first = aliasing_ ? requests[i].first : 0;
      it[i].last = aliasing_ ? requests[i].last : UINT32_MAX;
    }
  };
  if (reuse) {
    items = items_;
    lifetimes(items);
    reuse = planFits(plan_, items);
  }
  if (!reuse) {
    if (ctx_) release();
    ctx_ = &ctx;
    ++rebuilds_;
    for (size_t i = 0; i < requests.size(); ++i) {
      images_.push_back(rhi::Image::unbound(ctx, requests[i].desc, requests[i].name.c_str()));
      const VkMemoryRequirements req = images_.back().memoryRequirements();
      items[i] = {req.size, req.alignment, req.memoryTypeBits, 0, 0};
    }
    lifetimes(items);
    plan_ = packByLifetime(items);
    for (const AliasHeap& h : plan_.heaps)
      heaps_.push_back(ctx.memory().allocate({h.size, h.alignment, h.memoryTypeBits}, rhi::MemoryUsage::GpuOnly, false,
                                             rhi::MemoryCategory::Image));
    for (size_t i = 0; i < requests.size(); ++i) {
      const AliasPlacement& p = plan_.placements[i];
      images_[i].bindPlaced(heaps_[p.heap].memory, heaps_[p.heap].offset + p.offset, requests[i].name.c_str());
    }
  }
  items_ = std::move(items);
  requests_ = requests;
  before = aliasedBefore(plan_, items_);
  if (!reuse && log::level() <= log::Level::Debug)
    log::debug("transient images placed\n{}", formatMemoryReport(report()));
  std::vector<const rhi::Image*> out;
  for (const rhi::Image& img : images_) out.push_back(&img);
  return out;
}

void TransientPool::recordImported(const std::vector<std::pair<std::string, const rhi::Image*>>& imported) {
  imported_.clear();
  std::vector<const rhi::Image*> seen;
  for (const auto& [name, image] : imported) {
    if (std::find(seen.begin(), seen.end(), image) != seen.end()) continue;
    seen.push_back(image);
    FrameMemoryEntry e;
    e.name = name;
    e.desc = image->desc();
    e.bytes = image->bytes();
    e.imported = true;
    imported_.push_back(std::move(e));
  }
}

FrameMemoryReport TransientPool::report() const {
  FrameMemoryReport report;
  for (size_t i = 0; i < requests_.size(); ++i) {
    const TransientRequest& r = requests_[i];
    report.entries.push_back({r.name, r.desc, items_[i].size, false, int32_t(plan_.placements[i].heap),
                              plan_.placements[i].offset, r.firstPass, r.lastPass});
    report.transientUnaliasedBytes += items_[i].size;
  }
  report.transientBytes = plan_.totalBytes();
  for (const FrameMemoryEntry& e : imported_) {
    report.entries.push_back(e);
    report.importedBytes += e.bytes;
  }
  return report;
}

}  // namespace rayster::graph
