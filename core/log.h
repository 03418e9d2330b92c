#pragma once
// One-line diagnostics on stderr. Kept tiny on purpose: the CLI's stdout is reserved for
// machine-readable output (benchmarks, compare results), so everything human goes here.
#include <string_view>
#include <utility>

#include <fmt/format.h>

namespace rayster::log {

enum class Level { Debug, Info, Warn, Error };

void setLevel(Level level);
Level level();

namespace detail {
// Writes "rayster: <prefix><message>\n" as one write so concurrent lines do not interleave.
void write(Level level, std::string_view message);
}  // namespace detail

template <class... A>
void debug(fmt::format_string<A...> f, A&&... args) {
  if (level() <= Level::Debug) detail::write(Level::Debug, fmt::format(f, std::forward<A>(args)...));
}

template <class... A>
void info(fmt::format_string<A...> f, A&&... args) {
  if (level() <= Level::Info) detail::write(Level::Info, fmt::format(f, std::forward<A>(args)...));
}

template <class... A>
void warn(fmt::format_string<A...> f, A&&... args) {
  if (level() <= Level::Warn) detail::write(Level::Warn, fmt::format(f, std::forward<A>(args)...));
}

template <class... A>
void error(fmt::format_string<A...> f, A&&... args) {
  if (level() <= Level::Error) detail::write(Level::Error, fmt::format(f, std::forward<A>(args)...));
}

}  // namespace rayster::log
