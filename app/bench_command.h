#pragma once
// `rayster bench`: runs a plan of configurations, one child process each, and writes JSON, CSV and
// an SVG plot; `rayster bench --compare A B` reports significant per-pass changes between two runs.
#include <string>
#include <vector>

#include "app/bench_plan.h"
#include "app/bench_stats.h"

namespace rayster::app {

struct BenchOptions {
  BenchAxes axes;
  std::string plan;                           // a JSON plan instead of the axes
  std::string shard;                          // "i/n": run every n-th configuration (app/bench_shard.h)
  std::vector<std::string> merge;             // shard results to merge into --json instead of running
  std::string json = "bench-out/bench.json";  // results; CSV and SVG default to the same stem
  std::string csv, svg;
  std::vector<std::string> compare;  // two result files: compare instead of running
  double minChange = kDefaultMinChange;
  bool failOnChange = false;
  std::string child, childOut;  // internal: one configuration (JSON) in this process
  bool validation = false, debugLabels = true;
  std::string device;
};

int benchCommand(const BenchOptions& options);

}  // namespace rayster::app
