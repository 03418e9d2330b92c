#pragma once
// A parallel loop for loading work (image decoding, vertex conversion): plain std::threads that
// take indices from a shared counter, so uneven items (a 4K image next to a 64² one) balance. No
// pool is kept: a scene loads once, and starting a thread costs microseconds next to decoding.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace rayster {

// Worker threads parallelFor uses at most: the hardware's, or RAYSTER_THREADS when set (1 runs
// everything on the calling thread, for measurements and debugging).
unsigned loadThreads();

// Calls f(i) for every i in [0, n), on up to loadThreads() threads (the caller's among them), and
// returns when all are done. f must not throw; items must be independent.
template <class F>
void parallelFor(size_t n, F&& f) {
  const size_t threads = std::min<size_t>(loadThreads(), n);
  if (threads <= 1) {
    for (size_t i = 0; i < n; ++i) f(i);
    return;
  }
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t i = next.fetch_add(1); i < n; i = next.fetch_add(1)) f(i);
  };
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  for (size_t t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
}

}  // namespace rayster
