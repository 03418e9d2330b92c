#pragma once
// The `rayster` subcommands. Each returns the process exit code (core/error.h).
#include <string>
#include <vector>

namespace rayster::app {

int run(int argc, char** argv);

}  // namespace rayster::app
