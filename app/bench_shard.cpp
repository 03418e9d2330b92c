#include "app/bench_shard.h"

#include <algorithm>
#include <cstdio>
#include <set>

#include <fmt/format.h>

namespace rayster::app {

using nlohmann::json;

Result<Shard> parseShard(const std::string& text) {
  unsigned i = 0, n = 0;
  char slash = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%u%c%u%c", &i, &slash, &n, &extra) != 3 || slash != '/' || text[0] == '-' ||
      text.find('/') + 1 >= text.size() || text[text.find('/') + 1] == '-')
    return makeError(ExitCode::BadArguments, "--shard must be I/N (1-based: 1/4 is the first of four), got '{}'", text);
  if (n < 1 || n > 100000 || i < 1 || i > n)
    return makeError(ExitCode::BadArguments, "--shard {}: needs 1 <= I <= N <= 100000", text);
  return Shard{i, n};
}

BenchPlan shardOf(const BenchPlan& plan, const Shard& s) {
  BenchPlan part;
  part.name = plan.name;
  for (size_t k = s.index - 1; k < plan.configs.size(); k += s.count) part.configs.push_back(plan.configs[k]);
  return part;
}

json shardJson(const Shard& s, size_t planConfigs) {
  return {{"index", s.index}, {"count", s.count}, {"plan_configs", planConfigs}};
}

namespace {

// The shard's configurations of a plan of `total`: positions index-1, index-1+count, ...
size_t configsOfShard(size_t total, uint32_t index, uint32_t count) {
  return total < index ? 0 : (total - index) / count + 1;
}

}  // namespace

Result<json> mergeShards(const std::vector<json>& shards, const std::vector<std::string>& names) {
  if (shards.empty()) return makeError(ExitCode::BadArguments, "--merge needs the shards' result files");
  std::vector<const json*> byIndex;
  uint32_t count = 0;
  size_t total = 0;
  for (size_t f = 0; f < shards.size(); ++f) {
    const json& r = shards[f];
    const std::string& name = names[f];
    if (!r.is_object() || !r.contains("shard") || !r["shard"].is_object() || !r.contains("configs"))
      return makeError(ExitCode::BadInput, "--merge: {} is not the result of a bench --shard", name);
    const json& s = r["shard"];
    const uint32_t i = s.value("index", 0u), n = s.value("count", 0u);
    const size_t t = s.value("plan_configs", size_t(0));
    if (f == 0) {
      count = n;
      total = t;
      byIndex.assign(n + 1, nullptr);
    }
    const json& first = shards[0];
    if (n != count || t != total || r.value("plan", "") != first.value("plan", ""))
      return makeError(ExitCode::BadInput, "--merge: {} is shard {}/{} of plan \"{}\", {} of \"{}\"", name, i, n,
                       r.value("plan", ""), names[0], first.value("plan", ""));
    if (r.value("commit", "") != first.value("commit", ""))
      return makeError(ExitCode::BadInput, "--merge: {} was run by commit {}, {} by {}", name, r.value("commit", ""),
                       names[0], first.value("commit", ""));
    if (i < 1 || i > n) return makeError(ExitCode::BadInput, "--merge: {}: shard {}/{} is out of range", name, i, n);
    if (byIndex[i]) return makeError(ExitCode::BadInput, "--merge: shard {}/{} is given twice ({})", i, n, name);
    if (r["configs"].size() != configsOfShard(total, i, n))
      return makeError(ExitCode::BadInput, "--merge: {} holds {} configuration(s); shard {}/{} of {} has {}", name,
                       r["configs"].size(), i, n, total, configsOfShard(total, i, n));
    byIndex[i] = &r;
  }
  for (uint32_t i = 1; i <= count; ++i)
    if (!byIndex[i]) return makeError(ExitCode::BadInput, "--merge: shard {}/{} is missing", i, count);

  json merged = *byIndex[1];
  merged.erase("shard");
  merged["configs"] = json::array();
  std::set<std::string> hosts;
  for (uint32_t i = 1; i <= count; ++i) {
    const json& r = *byIndex[i];
    hosts.insert(r.value("host", ""));
    if (merged.value("device", "") == "") {
      merged["device"] = r.value("device", "");
      merged["driver"] = r.value("driver", "");
    }
    merged["date"] = std::min(merged.value("date", ""), r.value("date", ""));  // ISO 8601: the first start
  }
  std::string host;
  for (const std::string& h : hosts) host += (host.empty() ? "" : ",") + h;
  merged["host"] = host;
  for (size_t k = 0; k < total; ++k) merged["configs"].push_back((*byIndex[k % count + 1])["configs"][k / count]);
  return merged;
}

}  // namespace rayster::app
