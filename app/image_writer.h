#pragma once
// Encodes and writes a sequence's images on worker threads, so the render thread does not wait for
// PNG compression (0.45-2 s for a 1080p PNG on 2 cores, against a few ms of GPU time per frame on
// an H200). Every file goes through a temporary file in its folder and a rename (core/image_io.h).
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "core/error.h"

namespace rayster::app {

// Encoders: one core left for the render thread, at least 2 and at most 8 (RAYSTER_THREADS caps
// it, as it caps loading). A 1080p PNG takes ≈ 0.6 s to encode on an H200 host's core, against
// ≈ 4–70 ms to render: with 2 encoders a 1080p sequence ran at 3.3 frames/s there, bound by them.
// The queue holds twice as many frames, absorbing uneven encode times while bounding memory (a 1080p
// frame with its HDR image is about 40 MB).
unsigned writerThreads();
inline constexpr unsigned kWriterThreads = 2;  // the fewest

class ImageWriter {
 public:
  // One frame's writes, in order; it owns the images it writes.
  using Job = std::function<Status()>;

  // queueFrames 0: twice the threads.
  explicit ImageWriter(unsigned threads = writerThreads(), size_t queueFrames = 0);
  ~ImageWriter();  // finish()
  ImageWriter(const ImageWriter&) = delete;
  ImageWriter& operator=(const ImageWriter&) = delete;

  // Queues a frame, waiting while the queue is full. After a failure the job is dropped: the run
  // stops at the next check of failure().
  void push(Job job);
  // The first failed write, if any (later queued frames are then dropped, not written).
  std::optional<Error> failure() const;
  // Waits for every queued frame and stops the workers; the first failure, if any.
  Status finish();

  double encodeSeconds() const;  // time the workers spent encoding and writing, summed
  double waitSeconds() const;    // time the caller spent blocked in push() and finish()
  uint64_t jobsDone() const;

 private:
  void work();

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> queue_;
  size_t capacity_;
  size_t running_ = 0;
  bool stopping_ = false;
  std::optional<Error> failure_;
  double encodeSeconds_ = 0, waitSeconds_ = 0;
  uint64_t done_ = 0;
  std::vector<std::thread> workers_;
};

}  // namespace rayster::app
