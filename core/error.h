#pragma once
// Errors in tiers (docs/style.md §7):
//  - recoverable paths (files, scenes, device selection) return Result<T> carrying an Error;
//  - Vulkan failures go through VK_CHECK (rhi/vk_check.h), fatal in every build;
//  - programmer errors fail fast with RAYSTER_ASSERT, also in release builds.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <variant>

#include <fmt/format.h>

namespace rayster {

// Process exit codes, documented in README.md and `rayster --help`. Never renumber.
enum class ExitCode : int {
  Ok = 0,
  Failure = 1,            // anything not listed below
  BadArguments = 2,       // command line could not be parsed or is inconsistent
  BadInput = 3,           // a scene or image file is missing, unreadable or invalid
  NoDevice = 4,           // no Vulkan driver or no usable device
  MissingCapability = 5,  // the device lacks a required feature (e.g. ray tracing)
  DeviceLost = 6,         // VK_ERROR_DEVICE_LOST during rendering
  OutOfMemory = 7,        // host or device memory exhausted
  OutputFailed = 8,       // the output file could not be written
  TestFailed = 9,         // a comparison exceeded its budget (rayster compare)
};

struct Error {
  ExitCode code = ExitCode::Failure;
  std::string message;  // one line, says what and why, e.g. "scene.gltf: accessor 3 out of bounds"
};

template <class... Args>
Error makeError(ExitCode code, fmt::format_string<Args...> f, Args&&... args) {
  return Error{code, fmt::format(f, std::forward<Args>(args)...)};
}

// A minimal std::expected stand-in (g++ 12 has none).
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}
  Result(Error error) : v_(std::move(error)) {}
  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }
  T& value() & { return std::get<0>(v_); }
  T&& value() && { return std::get<0>(std::move(v_)); }
  const T& value() const& { return std::get<0>(v_); }
  T& operator*() & { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  const Error& error() const { return std::get<1>(v_); }

 private:
  std::variant<T, Error> v_;
};

struct Ok {};
using Status = Result<Ok>;
inline Status okStatus() { return Ok{}; }

[[noreturn]] inline void fatal(const char* what, const char* file, int line) {
  std::fprintf(stderr, "rayster: internal error: %s (%s:%d)\n", what, file, line);
  std::fflush(stderr);
  std::abort();
}

}  // namespace rayster

#define RAYSTER_ASSERT(cond, msg)                                                           \
  do {                                                                                      \
    if (!(cond)) ::rayster::fatal("assertion failed: " #cond ": " msg, __FILE__, __LINE__); \
  } while (0)

// Propagates an Error from an expression returning Result<T>.
#define RAYSTER_TRY(expr)                                \
  do {                                                   \
    auto&& rayster_try_ = (expr);                        \
    if (!rayster_try_.ok()) return rayster_try_.error(); \
  } while (0)
