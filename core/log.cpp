#include "core/log.h"

#include <atomic>
#include <cstdio>
#include <string>

namespace rayster::log {
namespace {
std::atomic<Level> gLevel{Level::Info};
}  // namespace

void setLevel(Level level) { gLevel.store(level, std::memory_order_relaxed); }
Level level() { return gLevel.load(std::memory_order_relaxed); }

namespace detail {
void write(Level level, std::string_view message) {
  const char* prefix = "rayster: ";
  if (level == Level::Warn) prefix = "rayster: warning: ";
  if (level == Level::Error) prefix = "rayster: error: ";
  std::string line = prefix;
  line.append(message);
  line.push_back('\n');
  std::fwrite(line.data(), 1, line.size(), stderr);
  std::fflush(stderr);
}
}  // namespace detail

}  // namespace rayster::log
