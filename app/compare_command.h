#pragma once
// `rayster compare REF TEST`: FLIP, HDR-FLIP, PSNR, RMSE and relative MSE between two images, with
// an optional mask, a heatmap, a JSON report and budgets (exit 9 when one is exceeded).
#include <string>
#include <vector>

#include "core/flip.h"

namespace rayster::app {

struct CompareOptions {
  std::string reference, test;
  std::vector<std::string> metrics;  // flip, hdr-flip, psnr, rmse, relmse, all; empty: all
  std::vector<std::string> budgets;  // METRIC=VALUE: flip, hdr-flip, rmse, relmse at most; psnr at least
  std::string mask;                  // PNG; pixels with nonzero rgb count
  std::string heatmap, json;         // outputs, written atomically
  double ppd = kDefaultPixelsPerDegree;
  int tolerance = 2;          // per-channel 8-bit steps for the "within tolerance" fraction
  double minFraction = -1.0;  // < 0: report only
};

int compareCommand(const CompareOptions& options);

}  // namespace rayster::app
