#include "core/parallel.h"

#include <cstdlib>

namespace rayster {

unsigned loadThreads() {
  static const unsigned threads = [] {
    if (const char* env = std::getenv("RAYSTER_THREADS")) {
      const long n = std::strtol(env, nullptr, 10);
      if (n >= 1 && n <= 1024) return unsigned(n);
    }
    return std::max(1u, std::thread::hardware_concurrency());
  }();
  return threads;
}

}  // namespace rayster
