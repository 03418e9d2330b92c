#pragma once
// Statistics of `rayster bench`: summaries of per-frame samples and the significance test behind
// `rayster bench --compare`.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rayster::app {

struct Summary {
  double median = 0, p5 = 0, p95 = 0, min = 0, max = 0, mean = 0;
};
// The "configs" array of a result file by reference (an empty one when missing), so pointers into
// it stay valid.
const nlohmann::json& configsOf(const nlohmann::json& results);

Summary summarize(std::vector<double> samples);  // all zero for an empty sample
nlohmann::json summaryJson(const Summary& s);

// Two-sided p-value of the Mann–Whitney U test (normal approximation with tie correction and
// continuity correction): the chance that samples this separated come from one distribution.
double mannWhitneyP(const std::vector<double>& a, const std::vector<double>& b);

// A change of one pass between two runs is reported when |Δmedian| > minChange (relative to the
// first run) AND it is significant: with at least kMinSamplesForU frames in both runs, the
// Mann–Whitney p < kSignificance; with fewer, the two runs' p5–p95 ranges do not overlap.
inline constexpr double kDefaultMinChange = 0.05;
inline constexpr double kSignificance = 0.01;
inline constexpr size_t kMinSamplesForU = 8;  // below this U's normal approximation is too coarse

struct PassChange {
  std::string config, pass;
  double medianA = 0, medianB = 0, relative = 0;  // (b - a) / a
  double p = 1;                                   // Mann–Whitney p; -1 when the range test decided
  std::string test;                               // "mann-whitney" or "p5-p95"
  bool flagged = false;
};

// Compares two `rayster bench` result files, configuration by id and pass by name (plus "frame",
// the per-frame GPU sum). Returns every pair found in both; `flagged` marks reported changes.
std::vector<PassChange> compareResults(const nlohmann::json& a, const nlohmann::json& b, double minChange);

}  // namespace rayster::app
