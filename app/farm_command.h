#pragma once
// `rayster farm slurm`: writes (and with --submit submits) the sbatch job array of a frame range
// or a bench plan (app/farm_slurm.h, docs/farm.md).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "app/farm_slurm.h"
#include "core/error.h"

namespace CLI {
class App;
}

namespace rayster::app {

struct FarmOptions {
  CLI::App* slurm = nullptr;  // the `farm slurm` subcommand
  std::string scene;
  std::vector<std::string> renderArgs;  // after `--`: passed to every `rayster render`
  std::string framesOut, output, hdr;
  uint64_t chunk = 0;
  std::string benchPlan, benchJson = "bench-out/bench.json";
  uint32_t shards = 0;
  std::string script;  // default <output folder>/slurm/<name>.sbatch; "-": stdout
  std::string logDir;  // default <output folder>/slurm
  std::string name;    // --job-name; default rayster-<output stem>
  std::string gres = "gpu:1";
  std::string partition, time, account, qos, constraint, mem;
  uint32_t cpusPerTask = 0;
  std::vector<std::string> sbatch;  // more sbatch options, one each
  uint32_t maxRetries = kDefaultMaxRetries;
  bool submit = false;
  // Checks the render options a task will be given as `rayster render` parses them (cli.cpp).
  std::function<Status(const std::vector<std::string>&)> checkRenderArgs;
};

// Adds `rayster farm` with its subcommand `slurm`; returns the `farm` command.
CLI::App* addFarmCommand(CLI::App& cli, FarmOptions& options);
int farmCommand(const FarmOptions& options);

// The job `options` describe, with every path made absolute; refused input is BadArguments or,
// for a missing scene or plan file, BadInput.
Result<SlurmJob> slurmJob(const FarmOptions& options);

}  // namespace rayster::app
