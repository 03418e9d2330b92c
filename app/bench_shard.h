#pragma once
// `rayster bench --plan PLAN --shard i/n` runs every n-th configuration of a plan, and
// `rayster bench --merge SHARDS... --json all.json` puts the shards' results back together, in the
// plan's order, equal to one process's run but for the timings (docs/farm.md). Shards are 1-based,
// as Slurm array tasks 1..n of `farm slurm --bench-plan`: shard i runs configurations i-1, i-1+n,
// i-1+2n, ... of the plan (0-based positions).
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench_plan.h"
#include "core/error.h"

namespace rayster::app {

struct Shard {
  uint32_t index = 1, count = 1;  // 1 <= index <= count
};

// "i/n" with 1 <= i <= n <= 100000; anything else is BadArguments.
Result<Shard> parseShard(const std::string& text);

// The configurations of `plan` that shard `s` runs, in plan order.
BenchPlan shardOf(const BenchPlan& plan, const Shard& s);

// The "shard" object of a shard's results: {"index", "count", "plan_configs"}.
nlohmann::json shardJson(const Shard& s, size_t planConfigs);

// Shard results (each with its "shard" object) as one result: every shard of one plan, commit and
// count exactly once, configurations in plan order; the "shard" objects go. Refused sets are
// BadInput with the cause.
Result<nlohmann::json> mergeShards(const std::vector<nlohmann::json>& shards, const std::vector<std::string>& names);

}  // namespace rayster::app
