#include "app/bench_stats.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace rayster::app {

namespace {
// Linear interpolation between order statistics (the "type 7" quantile of R and numpy).
double quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0;
  const double pos = q * double(sorted.size() - 1);
  const size_t i = size_t(std::floor(pos));
  const double f = pos - double(i);
  return i + 1 < sorted.size() ? sorted[i] * (1 - f) + sorted[i + 1] * f : sorted[i];
}
}  // namespace

const nlohmann::json& configsOf(const nlohmann::json& results) {
  static const nlohmann::json kEmpty = nlohmann::json::array();
  return results.is_object() && results.contains("configs") && results["configs"].is_array() ? results["configs"]
                                                                                             : kEmpty;
}

Summary summarize(std::vector<double> v) {
  Summary s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.median = quantile(v, 0.5);
  s.p5 = quantile(v, 0.05);
  s.p95 = quantile(v, 0.95);
  s.min = v.front();
  s.max = v.back();
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / double(v.size());
  return s;
}

nlohmann::json summaryJson(const Summary& s) {
  return {{"median", s.median}, {"p5", s.p5}, {"p95", s.p95}, {"min", s.min}, {"max", s.max}, {"mean", s.mean}};
}

double mannWhitneyP(const std::vector<double>& a, const std::vector<double>& b) {
  const double n1 = double(a.size()), n2 = double(b.size());
  if (a.empty() || b.empty()) return 1;
  // Rank the pooled sample, ties get their mean rank.
  std::vector<std::pair<double, int>> pooled;
  for (double x : a) pooled.push_back({x, 0});
  for (double x : b) pooled.push_back({x, 1});
  std::sort(pooled.begin(), pooled.end());
  double rankSumA = 0, tieTerm = 0;
  for (size_t i = 0; i < pooled.size();) {
    size_t j = i;
    while (j < pooled.size() && pooled[j].first == pooled[i].first) ++j;
    const double rank = 0.5 * double(i + 1 + j);  // mean of ranks i+1..j
    const double t = double(j - i);
    tieTerm += t * t * t - t;
    for (size_t k = i; k < j; ++k)
      if (pooled[k].second == 0) rankSumA += rank;
    i = j;
  }
  const double u = rankSumA - n1 * (n1 + 1) / 2;
  const double n = n1 + n2;
  const double mean = n1 * n2 / 2;
  const double variance = n1 * n2 / 12 * ((n + 1) - tieTerm / (n * (n - 1)));
  if (variance <= 0) return 1;  // every value equal
  const double z = std::max(0.0, std::abs(u - mean) - 0.5) / std::sqrt(variance);
  return std::erfc(z / std::sqrt(2.0));
}

namespace {

std::vector<double> samplesOf(const nlohmann::json& j) {
  std::vector<double> v;
  if (j.is_array())
    for (const auto& x : j)
      if (x.is_number()) v.push_back(x.get<double>());
  return v;
}

// pass name → samples, with the frame's GPU sum as "frame".
std::map<std::string, std::vector<double>> passSamples(const nlohmann::json& config) {
  std::map<std::string, std::vector<double>> m;
  if (config.contains("passes"))
    for (const auto& p : config["passes"]) m[p.value("name", "")] = samplesOf(p.value("samples_ms", nlohmann::json()));
  if (config.contains("frame") && config["frame"].contains("gpu_samples_ms"))
    m["frame"] = samplesOf(config["frame"]["gpu_samples_ms"]);
  return m;
}

}  // namespace

std::vector<PassChange> compareResults(const nlohmann::json& a, const nlohmann::json& b, double minChange) {
  std::vector<PassChange> changes;
  std::map<std::string, const nlohmann::json*> bConfigs;
  for (const auto& c : configsOf(b))
    if (c.value("ok", false)) bConfigs[c.value("id", "")] = &c;
  for (const auto& ca : configsOf(a)) {
    if (!ca.value("ok", false)) continue;
    auto it = bConfigs.find(ca.value("id", ""));
    if (it == bConfigs.end()) continue;
    const auto passesB = passSamples(*it->second);
    for (const auto& [pass, sa] : passSamples(ca)) {
      auto pb = passesB.find(pass);
      if (pb == passesB.end() || sa.empty() || pb->second.empty()) continue;
      const std::vector<double>& sb = pb->second;
      const Summary x = summarize(sa), y = summarize(sb);
      PassChange c;
      c.config = it->first;
      c.pass = pass;
      c.medianA = x.median;
      c.medianB = y.median;
      c.relative = x.median > 0 ? (y.median - x.median) / x.median : (y.median > 0 ? 1.0 : 0.0);
      bool significant = false;
      if (sa.size() >= kMinSamplesForU && sb.size() >= kMinSamplesForU) {
        c.test = "mann-whitney";
        c.p = mannWhitneyP(sa, sb);
        significant = c.p < kSignificance;
      } else {
        c.test = "p5-p95";
        c.p = -1;
        significant = x.p95 < y.p5 || y.p95 < x.p5;
      }
      c.flagged = std::abs(c.relative) > minChange && significant;
      changes.push_back(c);
    }
  }
  return changes;
}

}  // namespace rayster::app
