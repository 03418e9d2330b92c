#include "core/colormap.h"

#include <algorithm>
#include <cmath>

namespace rayster {
namespace {

// Entries 0, 16, 32, ..., 240 and 255 of matplotlib's _magma_data (sRGB in [0, 1]).
constexpr std::array<std::array<double, 3>, 17> kMagmaControl = {{
    {0.001462, 0.000466, 0.013866},
    {0.039608, 0.031090, 0.133515},
    {0.113094, 0.065492, 0.276784},
    {0.211718, 0.061992, 0.418647},
    {0.316654, 0.071690, 0.485380},
    {0.414709, 0.110431, 0.504662},
    {0.512831, 0.148179, 0.507648},
    {0.613617, 0.181811, 0.498536},
    {0.716387, 0.214982, 0.475290},
    {0.816914, 0.255895, 0.436461},
    {0.904281, 0.319610, 0.388137},
    {0.960949, 0.418323, 0.359630},
    {0.986700, 0.535582, 0.382210},
    {0.996096, 0.653659, 0.446213},
    {0.996898, 0.769591, 0.534892},
    {0.992440, 0.884330, 0.640099},
    {0.987053, 0.991438, 0.749504},
}};

int controlIndex(size_t i) { return i + 1 == kMagmaControl.size() ? 255 : static_cast<int>(i) * 16; }

}  // namespace

const std::array<Rgb8, 256>& magmaTable() {
  static const std::array<Rgb8, 256> table = [] {
    std::array<Rgb8, 256> t{};
    size_t segment = 0;
    for (int i = 0; i < 256; ++i) {
      while (controlIndex(segment + 1) < i) ++segment;
      const int i0 = controlIndex(segment), i1 = controlIndex(segment + 1);
      const double f = static_cast<double>(i - i0) / (i1 - i0);
      for (size_t c = 0; c < 3; ++c) {
        const double v = kMagmaControl[segment][c] + f * (kMagmaControl[segment + 1][c] - kMagmaControl[segment][c]);
        t[static_cast<size_t>(i)][c] = static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
      }
    }
    return t;
  }();
  return table;
}

}  // namespace rayster
