#include "app/frame_range.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <vector>

#include <fmt/format.h>

namespace rayster::app {
namespace {

bool parseNumber(const std::string& text, int64_t& value) {
  if (text.empty() || !std::all_of(text.begin(), text.end(), [](char c) { return std::isdigit((unsigned char)c); }))
    return false;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size();
}

std::vector<std::string> splitColons(const std::string& text) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t colon = text.find(':'); colon != std::string::npos; colon = text.find(':', start)) {
    parts.push_back(text.substr(start, colon - start));
    start = colon + 1;
  }
  parts.push_back(text.substr(start));
  return parts;
}

}  // namespace

Result<FrameRange> parseFrameRange(const std::string& text) {
  const std::vector<std::string> parts = splitColons(text);
  FrameRange r;
  if ((parts.size() != 2 && parts.size() != 3) || !parseNumber(parts[0], r.first) || !parseNumber(parts[1], r.last) ||
      (parts.size() == 3 && !parseNumber(parts[2], r.step)))
    return makeError(ExitCode::BadArguments,
                     "--frames-out must be FIRST:LAST or FIRST:LAST:STEP (frame numbers), got '{}'", text);
  if (r.last > kMaxFrameNumber)
    return makeError(ExitCode::BadArguments, "--frames-out {}: frame numbers go up to {}", text, kMaxFrameNumber);
  if (r.last < r.first)
    return makeError(ExitCode::BadArguments, "--frames-out {}: the last frame ({}) is before the first ({})", text,
                     r.last, r.first);
  if (r.step < 1) return makeError(ExitCode::BadArguments, "--frames-out {}: the step must be at least 1", text);
  return r;
}

bool hasFrameNumber(const std::string& path) {
  const size_t slash = path.rfind('/');
  return path.find('#', slash == std::string::npos ? 0 : slash + 1) != std::string::npos;
}

std::string framePath(const std::string& pattern, int64_t frame) {
  const size_t slash = pattern.rfind('/');
  std::string out = pattern.substr(0, slash == std::string::npos ? 0 : slash + 1);
  for (size_t i = out.size(); i < pattern.size();) {
    if (pattern[i] != '#') {
      out += pattern[i++];
      continue;
    }
    size_t run = 0;
    while (i + run < pattern.size() && pattern[i + run] == '#') ++run;
    out += fmt::format("{:0{}}", frame, run);
    i += run;
  }
  return out;
}

}  // namespace rayster::app
