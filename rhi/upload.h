#pragma once
// Uploads outside the frame (scene loading): buffers and pixels into sampled images, optionally
// with a full mip chain made by linear blits on the GPU. Barriers here are local to the upload (no
// graph involved).
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <span>
#include <vector>

#include "rhi/commands.h"
#include "rhi/resources.h"

namespace rayster::rhi {

class Context;

// `desc.mips` is ignored: 1, or the full chain when `generateMips`. Ends in SHADER_READ_ONLY_OPTIMAL.
Image uploadImage(Context& ctx, ImageDesc desc, std::span<const std::byte> pixels, bool generateMips, const char* name);

// Many uploads in few submissions (a scene's vertex, index and texture data): each goes through a
// staging chunk of kUploadChunkBytes; a full chunk's command buffer is submitted without waiting,
// so the device copies while the host fills the next. Each command buffer ends in a barrier from
// its transfers to every later command on the queue, so what is submitted afterwards (BLAS builds,
// frames) may read the data without waiting on the host. wait() (or the destructor) waits once.
// Where the device has a transfer-only queue (Context::hasTransferQueue()), an image's level 0 is
// copied there and handed to the universal queue (a queue-family ownership transfer), whose
// submission waits for the copies and then makes the mips: the copy engine uploads textures while
// the universal queue builds the BLASes. Buffers stay on the universal queue (the BLAS builds
// read them at once).
class UploadBatch {
 public:
  explicit UploadBatch(Context& ctx);
  ~UploadBatch();
  UploadBatch(const UploadBatch&) = delete;
  UploadBatch& operator=(const UploadBatch&) = delete;

  Buffer buffer(std::span<const std::byte> bytes, VkBufferUsageFlags usage, const char* name);
  // As uploadImage().
  Image image(ImageDesc desc, std::span<const std::byte> pixels, bool generateMips, const char* name);
  // Submits what is recorded (nothing waits); returns the timeline value that covers every upload
  // so far, 0 when nothing was ever submitted.
  uint64_t submit();
  // submit() and wait for it on the host.
  void wait();
  Context& context() const { return ctx_; }
  uint64_t bytes() const { return bytes_; }
  uint32_t submissions() const { return submissions_; }

 private:
  struct Staged {
    VkBuffer buffer;
    VkDeviceSize offset;
    std::byte* mapped;
  };
  Staged stage(size_t bytes);
  VkCommandBuffer cmd();

  Context& ctx_;
  std::unique_ptr<CommandList> list_;  // recording, or null
  // With a transfer queue: the images' copies and releases, and their acquires and mips; or null.
  std::unique_ptr<CommandList> transfer_, finish_;
  Buffer chunk_;
  VkDeviceSize used_ = 0;
  std::deque<uint64_t> inFlight_;  // timeline values of submitted chunks
  uint64_t last_ = 0, bytes_ = 0;
  uint32_t submissions_ = 0;
};

}  // namespace rayster::rhi
