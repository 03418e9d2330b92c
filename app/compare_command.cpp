// `rayster compare REF TEST`: how far one image is from another (docs/compare.md). Every input is
// checked before any work, and outputs are written atomically, so a failed run leaves no partial file.
#include "app/compare_command.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "core/metrics.h"

namespace rayster::app {
namespace {

enum class Metric { Flip, HdrFlip, Psnr, Rmse, RelMse };
constexpr std::array<Metric, 5> kAllMetrics = {Metric::Flip, Metric::HdrFlip, Metric::Psnr, Metric::Rmse,
                                               Metric::RelMse};
constexpr std::array<const char*, 5> kMetricNames = {"flip", "hdr-flip", "psnr", "rmse", "relmse"};
const char* name(Metric m) { return kMetricNames[static_cast<size_t>(m)]; }
std::optional<Metric> parseMetric(const std::string& text) {
  for (Metric m : kAllMetrics)
    if (text == name(m)) return m;
  return std::nullopt;
}
bool higherIsBetter(Metric m) { return m == Metric::Psnr; }

struct Budget {
  Metric metric;
  double limit;
};

struct Input {
  ImageF linear;
  bool hdr = false;  // EXR or Radiance HDR; PNGs are display-referred
};

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

Result<Input> load(const std::string& path, const char* role) {
  auto image = readImageLinear(path);
  if (!image) return image.error();
  if (image->empty()) return makeError(ExitCode::BadInput, "{} {} is empty", role, path);
  for (size_t i = 0; i < image->rgba.size(); ++i)
    if (i % 4 != 3 && !std::isfinite(image->rgba[i])) {
      const size_t p = i / 4, w = static_cast<size_t>(image->width);
      return makeError(ExitCode::BadInput, "{} {} has a non-finite value at pixel ({}, {})", role, path, p % w, p / w);
    }
  return Input{std::move(image).value(), lowerExtension(path) != ".png"};
}

// What PSNR and RMSE look at: the stored values, i.e. sRGB-encoded when both images are PNGs (the
// convention for 8-bit images), linear otherwise.
ImageF encoded(const ImageF& linear) {
  ImageF out = linear;
  for (size_t i = 0; i < out.rgba.size(); ++i)
    if (i % 4 != 3) out.rgba[i] = linearToSrgb(std::clamp(out.rgba[i], 0.0f, 1.0f));
  return out;
}

Result<std::vector<Metric>> parseMetrics(const std::vector<std::string>& names) {
  std::vector<Metric> metrics;
  for (const std::string& n : names) {
    if (n == "all") {
      metrics.assign(kAllMetrics.begin(), kAllMetrics.end());
      continue;
    }
    auto m = parseMetric(n);
    if (!m)
      return makeError(ExitCode::BadArguments, "--metric '{}' is not one of flip, hdr-flip, psnr, rmse, relmse, all",
                       n);
    if (std::find(metrics.begin(), metrics.end(), *m) == metrics.end()) metrics.push_back(*m);
  }
  if (names.empty()) metrics.assign(kAllMetrics.begin(), kAllMetrics.end());
  return metrics;
}

Result<std::vector<Budget>> parseBudgets(const std::vector<std::string>& texts) {
  std::vector<Budget> budgets;
  for (const std::string& t : texts) {
    const size_t eq = t.find('=');
    auto metric = eq == std::string::npos ? std::nullopt : parseMetric(t.substr(0, eq));
    char* end = nullptr;
    const std::string value = eq == std::string::npos ? "" : t.substr(eq + 1);
    const double limit = std::strtod(value.c_str(), &end);
    if (!metric || value.empty() || *end != '\0' || !std::isfinite(limit))
      return makeError(ExitCode::BadArguments,
                       "--budget '{}' must be METRIC=NUMBER with METRIC one of flip, hdr-flip, psnr, rmse, relmse", t);
    budgets.push_back({*metric, limit});
  }
  return budgets;
}

Status checkOutput(const std::string& path, const char* option, const char* extension) {
  if (path.empty() || lowerExtension(path) == extension) return okStatus();
  return makeError(ExitCode::BadArguments, "{} '{}' must end in {}", option, path, extension);
}

int fail(const Error& e) {
  std::fprintf(stderr, "rayster: error: %s\n", e.message.c_str());
  return static_cast<int>(e.code);
}

// Pixels (covered by the mask) whose 8-bit sRGB channels all lie within `tolerance` steps.
struct ToleranceStats {
  double fractionWithin = 1.0;
  int maxChannelDiff = 0;
};
ToleranceStats toleranceStats(const Image8& a, const Image8& b, int tolerance, const PixelMask& mask) {
  ToleranceStats s;
  size_t counted = 0, within = 0;
  for (size_t p = 0; p < a.rgba.size() / 4; ++p) {
    if (!mask.covers(p)) continue;
    int d = 0;
    for (size_t c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a.rgba[p * 4 + c]) - int(b.rgba[p * 4 + c])));
    s.maxChannelDiff = std::max(s.maxChannelDiff, d);
    ++counted;
    within += d <= tolerance;
  }
  if (counted > 0) s.fractionWithin = static_cast<double>(within) / static_cast<double>(counted);
  return s;
}

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

int compareCommand(const CompareOptions& o) {
  auto metrics = parseMetrics(o.metrics);
  if (!metrics) return fail(metrics.error());
  auto budgets = parseBudgets(o.budgets);
  if (!budgets) return fail(budgets.error());
  for (const Budget& b : *budgets)  // a budget needs its metric
    if (std::find(metrics->begin(), metrics->end(), b.metric) == metrics->end()) metrics->push_back(b.metric);
  auto wants = [&](Metric m) { return std::find(metrics->begin(), metrics->end(), m) != metrics->end(); };
  if (auto s = checkOutput(o.heatmap, "--heatmap", ".png"); !s) return fail(s.error());
  if (auto s = checkOutput(o.json, "--json", ".json"); !s) return fail(s.error());
  if (!o.mask.empty())
    if (auto s = checkOutput(o.mask, "--mask", ".png"); !s) return fail(s.error());
  if (!(o.ppd > 0)) return fail(makeError(ExitCode::BadArguments, "--ppd must be positive, got {}", o.ppd));

  auto ref = load(o.reference, "reference");
  if (!ref) return fail(ref.error());
  auto test = load(o.test, "test image");
  if (!test) return fail(test.error());
  const int w = ref->linear.width, h = ref->linear.height;
  if (test->linear.width != w || test->linear.height != h)
    return fail(makeError(ExitCode::BadInput, "sizes differ: reference {} is {}x{}, test {} is {}x{}", o.reference, w,
                          h, o.test, test->linear.width, test->linear.height));
  PixelMask mask;
  if (!o.mask.empty()) {
    auto image = readPng(o.mask);
    if (!image) return fail(image.error());
    if (image->width != w || image->height != h)
      return fail(makeError(ExitCode::BadInput, "mask {} is {}x{}, the images are {}x{}", o.mask, image->width,
                            image->height, w, h));
    mask = maskFromImage(*image);
    if (mask.count() == 0) return fail(makeError(ExitCode::BadInput, "mask {} covers no pixel (all black)", o.mask));
  }

  nlohmann::json report;
  report["reference"] = o.reference;
  report["test"] = o.test;
  report["width"] = w;
  report["height"] = h;
  report["mask"] = o.mask.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.mask);
  report["pixels"] = mask.empty() ? static_cast<size_t>(w) * h : mask.count();
  report["ppd"] = o.ppd;
  std::printf("%s vs %s: %dx%d, %zu pixels compared\n", o.reference.c_str(), o.test.c_str(), w, h,
              report["pixels"].get<size_t>());

  std::array<double, kAllMetrics.size()> values{};
  auto& jm = report["metrics"] = nlohmann::json::object();
  std::optional<ErrorMap> flipMap, hdrMap;
  if (wants(Metric::Flip)) {
    flipMap = flipLdr(ref->linear, test->linear, o.ppd);
    const ErrorStats s = errorStats(*flipMap, mask);
    values[size_t(Metric::Flip)] = s.mean;
    jm["flip"] = {{"mean", s.mean}, {"max", s.max}};
    std::printf("flip      %.6f  (mean; max %.4f; %.4g pixels per degree)\n", s.mean, s.max, o.ppd);
  }
  if (wants(Metric::HdrFlip)) {
    HdrFlipResult r = flipHdr(ref->linear, test->linear, o.ppd);
    const ErrorStats s = errorStats(r.map, mask);
    values[size_t(Metric::HdrFlip)] = s.mean;
    jm["hdr-flip"] = {
        {"mean", s.mean},
        {"max", s.max},
        {"exposures", {{"start", r.exposures.start}, {"stop", r.exposures.stop}, {"count", r.exposures.count}}}};
    std::printf("hdr-flip  %.6f  (mean; max %.4f; %d exposures %+.2f .. %+.2f EV)\n", s.mean, s.max, r.exposures.count,
                r.exposures.start, r.exposures.stop);
    hdrMap = std::move(r.map);
  }
  const bool linearDomain = ref->hdr || test->hdr;
  if (wants(Metric::Psnr) || wants(Metric::Rmse)) {
    const ImageF a = linearDomain ? ref->linear : encoded(ref->linear);
    const ImageF b = linearDomain ? test->linear : encoded(test->linear);
    values[size_t(Metric::Rmse)] = rmse(a, b, mask);
    values[size_t(Metric::Psnr)] = psnr(a, b, mask);
    report["rmsePsnrValues"] = linearDomain ? "linear" : "srgb";
    if (wants(Metric::Psnr)) {
      jm["psnr"] = number(values[size_t(Metric::Psnr)]);
      std::printf("psnr      %.4f dB  (%s values, peak 1)\n", values[size_t(Metric::Psnr)],
                  linearDomain ? "linear" : "sRGB");
    }
    if (wants(Metric::Rmse)) {
      jm["rmse"] = values[size_t(Metric::Rmse)];
      std::printf("rmse      %.6f  (%s values)\n", values[size_t(Metric::Rmse)], linearDomain ? "linear" : "sRGB");
    }
  }
  if (wants(Metric::RelMse)) {
    values[size_t(Metric::RelMse)] = relMse(ref->linear, test->linear, kRelMseEpsilon, mask);
    jm["relmse"] = values[size_t(Metric::RelMse)];
    std::printf("relmse    %.6f  (linear values, eps %g)\n", values[size_t(Metric::RelMse)], kRelMseEpsilon);
  }
  const Image8 ref8 = encodeSrgb8(ref->linear), test8 = encodeSrgb8(test->linear);
  const ToleranceStats tol = toleranceStats(ref8, test8, o.tolerance, mask);
  report["tolerance"] = {
      {"steps", o.tolerance}, {"fractionWithin", tol.fractionWithin}, {"maxChannelDiff", tol.maxChannelDiff}};
  std::printf("within %d/255: %.4f%% of pixels; max channel diff %d\n", o.tolerance, 100.0 * tol.fractionWithin,
              tol.maxChannelDiff);

  bool over = false;
  auto& jb = report["budgets"] = nlohmann::json::array();
  for (const Budget& b : *budgets) {
    const double v = values[static_cast<size_t>(b.metric)];
    const bool pass = higherIsBetter(b.metric) ? v >= b.limit : v <= b.limit;
    jb.push_back({{"metric", name(b.metric)}, {"limit", b.limit}, {"value", number(v)}, {"pass", pass}});
    if (!pass) {
      over = true;
      std::printf("over budget: %s %.6g %s %.6g\n", name(b.metric), v, higherIsBetter(b.metric) ? "<" : ">", b.limit);
    }
  }
  if (o.minFraction >= 0 && tol.fractionWithin < o.minFraction) {
    over = true;
    std::printf("over budget: %.4f%% < %.4f%% within %d/255\n", 100.0 * tol.fractionWithin, 100.0 * o.minFraction,
                o.tolerance);
  }
  report["overBudget"] = over;

  if (!o.heatmap.empty()) {
    // The FLIP map that matches the inputs (HDR-FLIP for an HDR reference); the 8-bit diff ramp if no
    // FLIP metric was asked for.
    const bool showHdr = hdrMap && (ref->hdr || !flipMap);
    const ErrorMap* map = showHdr ? &*hdrMap : flipMap ? &*flipMap : nullptr;
    const Image8 heat = map ? flipHeatmap(*map) : compare(ref8, test8, o.tolerance).heatmap;
    report["heatmap"] = {{"path", o.heatmap}, {"shows", showHdr ? "hdr-flip" : map ? "flip" : "8-bit diff"}};
    if (auto s = writePng(o.heatmap, heat); !s) return fail(s.error());
  }
  if (!o.json.empty())
    if (auto s = writeFileAtomically(o.json, report.dump(2) + "\n"); !s) return fail(s.error());
  return over ? static_cast<int>(ExitCode::TestFailed) : 0;
}

}  // namespace rayster::app
