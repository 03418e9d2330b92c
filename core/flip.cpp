// FLIP and HDR-FLIP, following the papers cited in flip.h step by step. Images are processed as
// float planes (one per channel) with separable filters and clamp-to-edge borders, so an image that
// is uniform stays uniform up to its edges.
#include "core/flip.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/colormap.h"
#include "core/error.h"

namespace rayster {
namespace {

using flip::Vec3;
using Plane = std::vector<float>;

// Every tunable of the papers, in one place.
constexpr double kColorExponent = 0.7;          // qc: HyAB differences are compressed by this power
constexpr double kFeatureExponent = 0.5;        // qf: and feature differences by this one
constexpr double kRedistributeCut = 0.4;        // pc: fraction of cmax ...
constexpr double kRedistributeTarget = 0.95;    // pt: ... mapped to this much of the error range
constexpr double kFeatureWidthDegrees = 0.082;  // w: feature size; the detectors' sigma is 0.5 w ppd
constexpr double kHdrTargetLuminance = 0.85;    // start/stop exposures tonemap max/median to this

// Contrast sensitivity functions, a1 exp(-b1 f^2) + a2 exp(-b2 f^2) in cycles per degree, per YyCxCz
// channel; their spatial form is a1 sqrt(pi/b1) exp(-pi^2 x^2 / b1) + (same for a2, b2), x in degrees.
struct Csf {
  double a1, b1, a2, b2;
};
constexpr std::array<Csf, 3> kCsf = {{
    {1.0, 0.0047, 0.0, 1e-5},   // achromatic
    {1.0, 0.0053, 0.0, 1e-5},   // red-green
    {34.1, 0.04, 13.5, 0.025},  // blue-yellow
}};

// One filter radius for all channels, three standard deviations of the widest Gaussian (b = 0.04).
int csfRadius(double ppd) {
  double widest = 0;
  for (const Csf& c : kCsf) widest = std::max({widest, c.b1, c.a2 > 0 ? c.b2 : 0.0});
  return static_cast<int>(std::ceil(3.0 * std::sqrt(widest / (2.0 * std::numbers::pi * std::numbers::pi)) * ppd));
}

// A CSF as a weighted sum of separable, individually normalised Gaussians: its 2-D kernel is
// sum_i weight_i * g_i(x) g_i(y), with the weights summing to 1.
struct SeparableTerm {
  double weight;
  std::vector<double> taps;  // sums to 1
};
std::vector<SeparableTerm> csfTerms(int channel, double ppd) {
  const Csf& c = kCsf[static_cast<size_t>(channel)];
  const int r = csfRadius(ppd);
  std::vector<SeparableTerm> terms;
  double total = 0;
  for (auto [a, b] : {std::pair{c.a1, c.b1}, std::pair{c.a2, c.b2}}) {
    if (a == 0) continue;
    SeparableTerm t{a * std::sqrt(std::numbers::pi / b), {}};
    double sum = 0;
    for (int i = -r; i <= r; ++i) {
      const double x = i / ppd;
      t.taps.push_back(std::exp(-std::numbers::pi * std::numbers::pi * x * x / b));
      sum += t.taps.back();
    }
    for (double& v : t.taps) v /= sum;
    t.weight *= sum * sum;  // the unnormalised 2-D term's total weight
    total += t.weight;
    terms.push_back(std::move(t));
  }
  for (SeparableTerm& t : terms) t.weight /= total;
  return terms;
}

// Scales positive weights to sum to 1 and negative ones to -1 (the papers' derivative normalisation).
void normalizeSigned(std::vector<double>& taps) {
  double positive = 0, negative = 0;
  for (double v : taps) (v > 0 ? positive : negative) += v;
  for (double& v : taps) v = v > 0 ? v / positive : (v < 0 ? v / -negative : 0.0);
}

std::vector<float> toFloat(const std::vector<double>& taps) { return {taps.begin(), taps.end()}; }

// out(x, y) = sum_j k[j] in(x + j - r, y) with clamped x (horizontal) or the same along y (vertical).
Plane convolve(const Plane& in, int w, int h, const std::vector<float>& k, bool horizontal) {
  const int r = static_cast<int>(k.size() / 2);
  Plane out(in.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float sum = 0;
      for (int j = -r; j <= r; ++j) {
        const int sx = horizontal ? std::clamp(x + j, 0, w - 1) : x;
        const int sy = horizontal ? y : std::clamp(y + j, 0, h - 1);
        sum += k[static_cast<size_t>(j + r)] * in[static_cast<size_t>(sy) * w + sx];
      }
      out[static_cast<size_t>(y) * w + x] = sum;
    }
  return out;
}

Plane separable(const Plane& in, int w, int h, const std::vector<float>& kx, const std::vector<float>& ky) {
  return convolve(convolve(in, w, h, kx, true), w, h, ky, false);
}

// Clamped linear rgb -> YyCxCz planes.
std::array<Plane, 3> toYcxczPlanes(const ImageF& image) {
  const size_t pixels = static_cast<size_t>(image.width) * image.height;
  std::array<Plane, 3> planes;
  for (Plane& p : planes) p.resize(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    Vec3 rgb;
    for (size_t c = 0; c < 3; ++c) rgb[c] = std::clamp(static_cast<double>(image.rgba[p * 4 + c]), 0.0, 1.0);
    const Vec3 v = flip::xyzToYcxcz(flip::linearRgbToXyz(rgb));
    for (size_t c = 0; c < 3; ++c) planes[c][p] = static_cast<float>(v[c]);
  }
  return planes;
}

// What the eye resolves of the image: each channel filtered by its CSF, back to rgb clamped to the
// gamut, then to Hunt-adjusted L*a*b*.
std::array<Plane, 3> perceivedLab(const std::array<Plane, 3>& ycxcz, int w, int h, double ppd) {
  std::array<Plane, 3> filtered;
  for (int c = 0; c < 3; ++c) {
    filtered[c].assign(ycxcz[c].size(), 0.0f);
    for (const SeparableTerm& t : csfTerms(c, ppd)) {
      const std::vector<float> taps = toFloat(t.taps);
      const Plane f = separable(ycxcz[c], w, h, taps, taps);
      for (size_t i = 0; i < f.size(); ++i) filtered[c][i] += static_cast<float>(t.weight) * f[i];
    }
  }
  for (size_t p = 0; p < filtered[0].size(); ++p) {
    Vec3 rgb = flip::xyzToLinearRgb(flip::ycxczToXyz({filtered[0][p], filtered[1][p], filtered[2][p]}));
    for (double& v : rgb) v = std::clamp(v, 0.0, 1.0);
    const Vec3 lab = flip::huntAdjust(flip::xyzToLab(flip::linearRgbToXyz(rgb)));
    for (size_t c = 0; c < 3; ++c) filtered[c][p] = static_cast<float>(lab[c]);
  }
  return filtered;
}

// Edge and point strength of the achromatic channel (Y / Yn, in [0, 1]) per pixel.
struct Features {
  Plane edge, point;
};
Features detectFeatures(const Plane& yy, int w, int h, const flip::FeatureKernels& k) {
  Plane y(yy.size());
  for (size_t i = 0; i < y.size(); ++i) y[i] = (yy[i] + 16.0f) / 116.0f;
  const std::vector<float> g = toFloat(k.gaussian), d1 = toFloat(k.firstDerivative), d2 = toFloat(k.secondDerivative);
  const Plane ex = separable(y, w, h, d1, g), ey = separable(y, w, h, g, d1);
  const Plane px = separable(y, w, h, d2, g), py = separable(y, w, h, g, d2);
  Features f{Plane(y.size()), Plane(y.size())};
  for (size_t i = 0; i < y.size(); ++i) {
    f.edge[i] = std::hypot(ex[i], ey[i]);
    f.point[i] = std::hypot(px[i], py[i]);
  }
  return f;
}

}  // namespace

double pixelsPerDegree(double distanceMeters, double widthMeters, double resolutionX) {
  return distanceMeters * (resolutionX / widthMeters) * std::numbers::pi / 180.0;
}

namespace flip {

Vec3 linearRgbToXyz(const Vec3& c) {
  return {0.4124564 * c[0] + 0.3575761 * c[1] + 0.1804375 * c[2],
          0.2126729 * c[0] + 0.7151522 * c[1] + 0.0721750 * c[2],
          0.0193339 * c[0] + 0.1191920 * c[1] + 0.9503041 * c[2]};
}

Vec3 xyzToLinearRgb(const Vec3& c) {
  return {3.2404542 * c[0] - 1.5371385 * c[1] - 0.4985314 * c[2],
          -0.9692660 * c[0] + 1.8760108 * c[1] + 0.0415560 * c[2],
          0.0556434 * c[0] - 0.2040259 * c[1] + 1.0572252 * c[2]};
}

Vec3 referenceWhite() { return linearRgbToXyz({1.0, 1.0, 1.0}); }

Vec3 xyzToYcxcz(const Vec3& xyz) {
  const Vec3 n = referenceWhite();
  const double x = xyz[0] / n[0], y = xyz[1] / n[1], z = xyz[2] / n[2];
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}

Vec3 ycxczToXyz(const Vec3& v) {
  const Vec3 n = referenceWhite();
  const double y = (v[0] + 16.0) / 116.0;
  return {(v[1] / 500.0 + y) * n[0], y * n[1], (y - v[2] / 200.0) * n[2]};
}

Vec3 xyzToLab(const Vec3& xyz) {
  const Vec3 n = referenceWhite();
  constexpr double delta = 6.0 / 29.0;
  auto f = [](double t) { return t > delta * delta * delta ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0; };
  const double fx = f(xyz[0] / n[0]), fy = f(xyz[1] / n[1]), fz = f(xyz[2] / n[2]);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Vec3 huntAdjust(const Vec3& lab) { return {lab[0], 0.01 * lab[0] * lab[1], 0.01 * lab[0] * lab[2]}; }

double hyab(const Vec3& a, const Vec3& b) { return std::abs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]); }

double maxColorDifference() {
  static const double cmax = [] {
    const Vec3 green = huntAdjust(xyzToLab(linearRgbToXyz({0.0, 1.0, 0.0})));
    const Vec3 blue = huntAdjust(xyzToLab(linearRgbToXyz({0.0, 0.0, 1.0})));
    return std::pow(hyab(green, blue), kColorExponent);
  }();
  return cmax;
}

double redistributeColorError(double powered, double cmax) {
  const double cut = kRedistributeCut * cmax;
  if (powered < cut) return kRedistributeTarget / cut * powered;
  return std::min(1.0, kRedistributeTarget + (powered - cut) / (cmax - cut) * (1.0 - kRedistributeTarget));
}

std::vector<double> csfKernel(int channel, double ppd) {
  RAYSTER_ASSERT(channel >= 0 && channel < 3, "CSF channel is 0, 1 or 2");
  const int side = 2 * csfRadius(ppd) + 1;
  std::vector<double> kernel(static_cast<size_t>(side) * side, 0.0);
  for (const SeparableTerm& t : csfTerms(channel, ppd))
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) kernel[static_cast<size_t>(y) * side + x] += t.weight * t.taps[x] * t.taps[y];
  return kernel;
}

FeatureKernels featureKernels(double ppd) {
  const double sigma = 0.5 * kFeatureWidthDegrees * ppd;  // in pixels
  const int r = static_cast<int>(std::ceil(3.0 * sigma));
  FeatureKernels k;
  double sum = 0;
  for (int i = -r; i <= r; ++i) {
    const double x = i, g = std::exp(-x * x / (2.0 * sigma * sigma));
    k.gaussian.push_back(g);
    k.firstDerivative.push_back(-x / (sigma * sigma) * g);
    k.secondDerivative.push_back((x * x / (sigma * sigma) - 1.0) / (sigma * sigma) * g);
    sum += g;
  }
  for (double& v : k.gaussian) v /= sum;
  normalizeSigned(k.firstDerivative);
  normalizeSigned(k.secondDerivative);
  return k;
}

// ACES fit (Narkowicz 2015) with its 0.6 input scale folded in, as in the HDR-FLIP paper:
// y = (k0 x^2 + k1 x + k2) / (k3 x^2 + k4 x + k5).
namespace {
constexpr std::array<double, 6> kTonemap = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};
}

double tonemap(double x) {
  const auto& k = kTonemap;
  return std::clamp((k[0] * x * x + k[1] * x + k[2]) / (k[3] * x * x + k[4] * x + k[5]), 0.0, 1.0);
}

double tonemapInverse(double y) {
  // (y k3 - k0) x^2 + (y k4 - k1) x + (y k5 - k2) = 0; the curve rises monotonically on x >= 0, so
  // the larger root is the one on that branch.
  const auto& k = kTonemap;
  const double a = y * k[3] - k[0], b = y * k[4] - k[1], c = y * k[5] - k[2];
  const double root = std::sqrt(std::max(0.0, b * b - 4.0 * a * c));
  const double x1 = (-b + root) / (2.0 * a), x2 = (-b - root) / (2.0 * a);
  return std::max(x1, x2);
}

}  // namespace flip

ErrorMap flipLdr(const ImageF& reference, const ImageF& test, double ppd) {
  RAYSTER_ASSERT(reference.width == test.width && reference.height == test.height, "FLIP needs images of equal size");
  RAYSTER_ASSERT(reference.rgba.size() == test.rgba.size(), "FLIP needs images of equal size");
  RAYSTER_ASSERT(ppd > 0, "FLIP needs a positive pixels-per-degree");
  const int w = reference.width, h = reference.height;
  ErrorMap map{w, h, std::vector<float>(reference.rgba.size() / 4, 0.0f)};
  if (map.values.empty()) return map;

  const std::array<Plane, 3> refYcxcz = toYcxczPlanes(reference), testYcxcz = toYcxczPlanes(test);
  const std::array<Plane, 3> refLab = perceivedLab(refYcxcz, w, h, ppd), testLab = perceivedLab(testYcxcz, w, h, ppd);
  const flip::FeatureKernels kernels = flip::featureKernels(ppd);
  const Features refFeatures = detectFeatures(refYcxcz[0], w, h, kernels);
  const Features testFeatures = detectFeatures(testYcxcz[0], w, h, kernels);
  const double cmax = flip::maxColorDifference();

  for (size_t p = 0; p < map.values.size(); ++p) {
    const double hyab =
        flip::hyab({refLab[0][p], refLab[1][p], refLab[2][p]}, {testLab[0][p], testLab[1][p], testLab[2][p]});
    const double color = flip::redistributeColorError(std::pow(hyab, kColorExponent), cmax);
    const double edge = std::abs(refFeatures.edge[p] - testFeatures.edge[p]);
    const double point = std::abs(refFeatures.point[p] - testFeatures.point[p]);
    const double feature = std::pow(std::max(edge, point) / std::numbers::sqrt2, kFeatureExponent);
    map.values[p] = static_cast<float>(std::pow(color, 1.0 - feature));
  }
  return map;
}

HdrExposures hdrFlipExposures(const ImageF& reference) {
  std::vector<double> luminance;
  luminance.reserve(reference.rgba.size() / 4);
  for (size_t i = 0; i < reference.rgba.size(); i += 4) {
    const double y = 0.2126 * reference.rgba[i] + 0.7152 * reference.rgba[i + 1] + 0.0722 * reference.rgba[i + 2];
    luminance.push_back(std::isfinite(y) ? std::max(0.0, y) : 0.0);
  }
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const double maxLuminance = luminance.empty() ? 0.0 : *std::max_element(luminance.begin(), luminance.end());
  if (!(maxLuminance > 0)) return {0.0, 0.0, 2};
  double medianLuminance = median(luminance);
  if (!(medianLuminance > 0)) {
    std::vector<double> lit;
    for (double y : luminance)
      if (y > 0) lit.push_back(y);
    medianLuminance = median(lit);
  }
  const double x = flip::tonemapInverse(kHdrTargetLuminance);
  HdrExposures e;
  e.start = std::log2(x / maxLuminance);
  e.stop = std::log2(x / medianLuminance);
  e.count = std::max(2, static_cast<int>(std::ceil(e.stop - e.start)));
  return e;
}

HdrFlipResult flipHdr(const ImageF& reference, const ImageF& test, double ppd) {
  return flipHdr(reference, test, ppd, hdrFlipExposures(reference));
}

HdrFlipResult flipHdr(const ImageF& reference, const ImageF& test, double ppd, const HdrExposures& exposures) {
  RAYSTER_ASSERT(reference.width == test.width && reference.height == test.height, "FLIP needs images of equal size");
  RAYSTER_ASSERT(exposures.count >= 1, "HDR-FLIP needs at least one exposure");
  HdrFlipResult result{{reference.width, reference.height, std::vector<float>(reference.rgba.size() / 4, 0.0f)},
                       exposures};
  auto expose = [](const ImageF& image, double scale) {
    ImageF out = image;
    for (size_t i = 0; i < out.rgba.size(); i += 4)
      for (size_t c = 0; c < 3; ++c)
        out.rgba[i + c] = static_cast<float>(flip::tonemap(scale * std::max(0.0f, image.rgba[i + c])));
    return out;
  };
  for (int i = 0; i < exposures.count; ++i) {
    const double scale = std::exp2(exposures.at(i));
    const ErrorMap map = flipLdr(expose(reference, scale), expose(test, scale), ppd);
    for (size_t p = 0; p < map.values.size(); ++p) result.map.values[p] = std::max(result.map.values[p], map.values[p]);
  }
  return result;
}

ErrorStats errorStats(const ErrorMap& map, const PixelMask& mask) {
  RAYSTER_ASSERT(
      mask.empty() || (mask.width == map.width && mask.height == map.height && mask.inside.size() == map.values.size()),
      "the mask must match the map's size");
  ErrorStats s;
  double sum = 0;
  for (size_t p = 0; p < map.values.size(); ++p) {
    if (!mask.covers(p)) continue;
    sum += map.values[p];
    s.max = std::max(s.max, static_cast<double>(map.values[p]));
    ++s.pixels;
  }
  s.mean = s.pixels == 0 ? 0.0 : sum / static_cast<double>(s.pixels);
  return s;
}

Image8 flipHeatmap(const ErrorMap& map) {
  const auto& table = magmaTable();
  Image8 out = Image8::make(map.width, map.height);
  for (size_t p = 0; p < map.values.size(); ++p) {
    const float v = std::isfinite(map.values[p]) ? std::clamp(map.values[p], 0.0f, 1.0f) : 1.0f;
    const auto& rgb = table[static_cast<size_t>(std::lround(v * 255.0f))];
    std::copy(rgb.begin(), rgb.end(), out.rgba.begin() + static_cast<std::ptrdiff_t>(p * 4));
    out.rgba[p * 4 + 3] = 255;
  }
  return out;
}

}  // namespace rayster
