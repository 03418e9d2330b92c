#include "rhi/commands.h"

#include "rhi/context.h"
#include "rhi/vk_check.h"

namespace rayster::rhi {

CommandList::CommandList(Context& ctx, Queue queue) : ctx_(ctx), queue_(queue) {
  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = queue == Queue::Transfer ? ctx.transferFamily() : ctx.queueFamily();
  VK_CHECK(vkCreateCommandPool(ctx.device(), &pci, nullptr, &pool_));
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VK_CHECK(vkAllocateCommandBuffers(ctx.device(), &ai, &cmd_));
}

CommandList::~CommandList() {
  ctx_.retire([dev = ctx_.device(), pool = pool_] { vkDestroyCommandPool(dev, pool, nullptr); });
}

VkCommandBuffer CommandList::begin() {
  VK_CHECK(vkResetCommandBuffer(cmd_, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd_, &bi));
  return cmd_;
}

uint64_t CommandList::submit() {
  VK_CHECK(vkEndCommandBuffer(cmd_));
  return queue_ == Queue::Transfer ? ctx_.submitTransfer(cmd_) : ctx_.submit(cmd_);
}

uint64_t CommandList::submitAfterTransfer(uint64_t value) {
  VK_CHECK(vkEndCommandBuffer(cmd_));
  return ctx_.submitAfterTransfer(cmd_, value);
}

void OneShot::submitAndWait() { ctx_.wait(list_.submit()); }

TimestampPool::TimestampPool(Context& ctx, uint32_t maxRegions) : ctx_(ctx), capacity_(maxRegions) {
  if (!ctx.caps().timestamps) return;
  VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  ci.queryCount = maxRegions * 2;
  VK_CHECK(vkCreateQueryPool(ctx.device(), &ci, nullptr, &pool_));
}

TimestampPool::~TimestampPool() {
  if (pool_) ctx_.retire([dev = ctx_.device(), p = pool_] { vkDestroyQueryPool(dev, p, nullptr); });
}

void TimestampPool::reset(VkCommandBuffer cmd) {
  names_.clear();
  if (pool_) vkCmdResetQueryPool(cmd, pool_, 0, capacity_ * 2);
}

uint32_t TimestampPool::begin(VkCommandBuffer cmd, std::string name) {
  if (!pool_ || names_.size() >= capacity_) return UINT32_MAX;
  uint32_t region = uint32_t(names_.size());
  names_.push_back(std::move(name));
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, region * 2);
  return region;
}

void TimestampPool::end(VkCommandBuffer cmd, uint32_t region) {
  if (region == UINT32_MAX) return;
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, region * 2 + 1);
}

std::vector<TimestampPool::Timing> TimestampPool::read() {
  std::vector<Timing> out;
  if (!pool_ || names_.empty()) return out;
  std::vector<uint64_t> ticks(names_.size() * 2);
  VK_CHECK(vkGetQueryPoolResults(ctx_.device(), pool_, 0, uint32_t(ticks.size()), ticks.size() * sizeof(uint64_t),
                                 ticks.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  for (size_t i = 0; i < names_.size(); ++i) {
    double ns = double(ticks[2 * i + 1] - ticks[2 * i]) * ctx_.caps().timestampPeriodNs;
    out.push_back({names_[i], ns * 1e-6});
  }
  return out;
}

}  // namespace rayster::rhi
