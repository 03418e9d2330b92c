#include "app/image_writer.h"

#include <algorithm>
#include <chrono>

#include "core/parallel.h"

namespace rayster::app {
namespace {
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

unsigned writerThreads() {
  const unsigned cores = std::max(1u, std::min(std::thread::hardware_concurrency(), loadThreads()));
  return std::clamp(cores > 1 ? cores - 1 : 1u, kWriterThreads, 8u);
}

ImageWriter::ImageWriter(unsigned threads, size_t queueFrames)
    : capacity_(queueFrames > 0 ? queueFrames : 2 * size_t(std::max(1u, threads))) {
  for (unsigned i = 0; i < std::max(1u, threads); ++i) workers_.emplace_back([this] { work(); });
}

ImageWriter::~ImageWriter() { (void)finish(); }

void ImageWriter::push(Job job) {
  const Clock::time_point start = Clock::now();
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.size() < capacity_ || failure_; });
  waitSeconds_ += secondsSince(start);
  if (failure_) return;
  queue_.push_back(std::move(job));
  changed_.notify_all();
}

std::optional<Error> ImageWriter::failure() const {
  std::lock_guard lock(mutex_);
  return failure_;
}

Status ImageWriter::finish() {
  const Clock::time_point start = Clock::now();
  {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return (queue_.empty() && running_ == 0) || workers_.empty(); });
    stopping_ = true;
    changed_.notify_all();
  }
  for (std::thread& t : workers_) t.join();
  std::lock_guard lock(mutex_);
  if (!workers_.empty()) waitSeconds_ += secondsSince(start);
  workers_.clear();
  if (failure_) return *failure_;
  return okStatus();
}

void ImageWriter::work() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return !queue_.empty() || stopping_; });
    if (queue_.empty()) return;  // stopping, nothing left
    Job job = std::move(queue_.front());
    queue_.pop_front();
    if (failure_) {  // drop what was queued after a failure
      changed_.notify_all();
      continue;
    }
    ++running_;
    lock.unlock();
    const Clock::time_point start = Clock::now();
    Status written = job();
    const double seconds = secondsSince(start);
    job = nullptr;  // free the images outside the lock's wait
    lock.lock();
    --running_;
    encodeSeconds_ += seconds;
    ++done_;
    if (!written && !failure_) failure_ = written.error();
    changed_.notify_all();
  }
}

double ImageWriter::encodeSeconds() const {
  std::lock_guard lock(mutex_);
  return encodeSeconds_;
}
double ImageWriter::waitSeconds() const {
  std::lock_guard lock(mutex_);
  return waitSeconds_;
}
uint64_t ImageWriter::jobsDone() const {
  std::lock_guard lock(mutex_);
  return done_;
}

}  // namespace rayster::app
