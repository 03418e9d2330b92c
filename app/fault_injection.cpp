#include "app/fault_injection.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace rayster::app {

Result<std::optional<InjectedFailure>> parseInjectedFailure(const char* value) {
  if (!value || !*value) return std::optional<InjectedFailure>{};
  char kind[8] = {}, extra = 0;
  long long frame = -1;
  const bool parsed = std::sscanf(value, "%7[a-z]:%lld%c", kind, &frame, &extra) == 2 && frame >= 0;
  const bool lost = parsed && std::strcmp(kind, "lost") == 0, oom = parsed && std::strcmp(kind, "oom") == 0;
  if (!lost && !oom)
    return makeError(ExitCode::BadArguments, "{} must be lost:FRAME or oom:FRAME, got '{}'", kRenderFailAtVariable,
                     value);
  return std::optional<InjectedFailure>{
      InjectedFailure{lost ? VK_ERROR_DEVICE_LOST : VK_ERROR_OUT_OF_DEVICE_MEMORY, int64_t(frame)}};
}

Result<std::optional<InjectedFailure>> injectedRenderFailure() {
  return parseInjectedFailure(std::getenv(kRenderFailAtVariable));
}

}  // namespace rayster::app
