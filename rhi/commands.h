#pragma once
// Command buffers and GPU timestamps.
#include <cstdint>
#include <string>
#include <vector>

#include <volk.h>

namespace rayster::rhi {

class Context;

enum class Queue { Universal, Transfer };

// A command pool with one primary command buffer, re-recorded each use, for the universal queue
// or the transfer queue (Context::hasTransferQueue()).
class CommandList {
 public:
  explicit CommandList(Context& ctx, Queue queue = Queue::Universal);
  ~CommandList();
  CommandList(const CommandList&) = delete;
  CommandList& operator=(const CommandList&) = delete;
  VkCommandBuffer begin();  // resets and begins recording
  uint64_t submit();        // ends and submits; returns the (its queue's) timeline value to wait for
  // Universal lists only: ends and submits, its commands waiting for transfer submission `value`.
  uint64_t submitAfterTransfer(uint64_t value);
  VkCommandBuffer handle() const { return cmd_; }
  operator VkCommandBuffer() const { return cmd_; }

 private:
  Context& ctx_;
  Queue queue_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
};

// For uploads and builds outside the frame: records on construction, submitAndWait() runs it.
class OneShot {
 public:
  explicit OneShot(Context& ctx) : list_(ctx), ctx_(ctx) { list_.begin(); }
  void submitAndWait();
  operator VkCommandBuffer() const { return list_.handle(); }

 private:
  CommandList list_;
  Context& ctx_;
};

// A pool of timestamp pairs, one per named region, read back after the frame's submission.
class TimestampPool {
 public:
  TimestampPool(Context& ctx, uint32_t maxRegions);
  ~TimestampPool();
  TimestampPool(const TimestampPool&) = delete;
  TimestampPool& operator=(const TimestampPool&) = delete;
  void reset(VkCommandBuffer cmd);  // at the start of a frame
  // Returns a region index, or UINT32_MAX when timestamps are unsupported or the pool is full.
  uint32_t begin(VkCommandBuffer cmd, std::string name);
  void end(VkCommandBuffer cmd, uint32_t region);
  struct Timing {
    std::string name;
    double ms;
  };
  std::vector<Timing> read();  // after the submission completed

 private:
  Context& ctx_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t capacity_ = 0;
  std::vector<std::string> names_;
};

}  // namespace rayster::rhi
