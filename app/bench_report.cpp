#include "app/bench_report.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include <fmt/format.h>

#include "app/bench_stats.h"

namespace rayster::app {

namespace {

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string xmlEscape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '&':
        o += "&amp;";
        break;
      case '"':
        o += "&quot;";
        break;
      default:
        o += c;
    }
  }
  return o;
}

// A palette of distinguishable hues, one per pass name in order of first appearance.
std::string colour(size_t i) {
  static const char* kPalette[] = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948", "#b07aa1",
                                   "#ff9da7", "#9c755f", "#bab0ac", "#1f77b4", "#d62728", "#2ca02c", "#9467bd"};
  return kPalette[i % (sizeof(kPalette) / sizeof(kPalette[0]))];
}

double frameMedian(const nlohmann::json& c) {
  return c.contains("frame") ? c["frame"]["gpu_ms"].value("median", 0.0) : 0.0;
}

}  // namespace

std::string axisValue(const nlohmann::json& c) {
  const std::string axis = c.value("axis", "");
  if (axis == "size") return fmt::format("{}x{}", c.value("width", 0), c.value("height", 0));
  if (axis == "max_depth") return fmt::format("depth {}", c.value("max_depth", 0));
  if (axis == "primary") return c.value("primary", "");
  if (axis == "mode") return c.value("mode", "");
  if (axis == "triangles" && c.contains("scene_stats"))
    return fmt::format("{} tris", c["scene_stats"].value("triangles", uint64_t(0)));
  if (axis == "lights" && c.contains("scene_stats"))
    return fmt::format("{} lights", c["scene_stats"].value("lights", 0u));
  return c.value("scene", "");
}

std::string benchCsv(const nlohmann::json& results) {
  std::string out =
      "id,sweep,axis,x,scene,width,height,mode,primary,max_depth,pass,median_ms,p95_ms,min_ms,rays,grays_per_s\n";
  for (const auto& c : configsOf(results)) {
    if (!c.value("ok", false)) continue;
    const std::string head = fmt::format(
        "{},{},{},{},{},{},{},{},{},{}", csvField(c.value("id", "")), csvField(c.value("sweep", "")),
        csvField(c.value("axis", "")), csvField(axisValue(c)), csvField(c.value("scene", "")), c.value("width", 0),
        c.value("height", 0), c.value("mode", ""), c.value("primary_used", ""), c.value("max_depth", 0));
    for (const auto& p : c["passes"])
      out += fmt::format("{},{},{:.6f},{:.6f},{:.6f},{},{:.4f}\n", head, csvField(p.value("name", "")),
                         p.value("median_ms", 0.0), p.value("p95_ms", 0.0), p.value("min_ms", 0.0),
                         p.value("rays", uint64_t(0)), p.value("grays_per_s", 0.0));
    const auto& g = c["frame"]["gpu_ms"];
    out +=
        fmt::format("{},frame,{:.6f},{:.6f},{:.6f},{},{:.4f}\n", head, g.value("median", 0.0), g.value("p95", 0.0),
                    g.value("min", 0.0), c["frame"].value("rays", uint64_t(0)), c["frame"].value("grays_per_s", 0.0));
  }
  return out;
}

std::string benchSvg(const nlohmann::json& results) {
  // Sweeps in order of first appearance, each with its successful configurations.
  std::vector<std::string> sweepOrder;
  std::map<std::string, std::vector<const nlohmann::json*>> sweeps;
  std::vector<std::string> passNames;
  for (const auto& c : configsOf(results)) {
    if (!c.value("ok", false)) continue;
    const std::string s = c.value("sweep", "");
    if (!sweeps.count(s)) sweepOrder.push_back(s);
    sweeps[s].push_back(&c);
    for (const auto& p : c["passes"])
      if (std::find(passNames.begin(), passNames.end(), p.value("name", "")) == passNames.end())
        passNames.push_back(p.value("name", ""));
  }
  constexpr double kWidth = 960, kChartH = 260, kTop = 40, kLeft = 70, kLegendW = 200;
  constexpr double kSection = kChartH * 2 + 120;
  const double height = kTop + std::max<size_t>(sweepOrder.size(), 1) * kSection;
  std::string svg = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0f}\" "
      "height=\"{:.0f}\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" "
      "fill=\"white\"/>\n<text x=\"10\" y=\"22\" font-size=\"15\">rayster bench: {} ({}, commit {})</text>\n",
      kWidth + kLegendW, height, xmlEscape(results.value("plan", "")), xmlEscape(results.value("device", "")),
      xmlEscape(results.value("commit", "")));
  const double plotW = kWidth - kLeft - 20;
  for (size_t si = 0; si < sweepOrder.size(); ++si) {
    const auto& configs = sweeps[sweepOrder[si]];
    const double y0 = kTop + double(si) * kSection;
    svg += fmt::format(
        "<g class=\"sweep\" id=\"sweep-{}\">\n<text x=\"10\" y=\"{:.1f}\" font-size=\"13\">sweep {}: "
        "per-pass GPU ms (median), stacked</text>\n",
        xmlEscape(sweepOrder[si]), y0 + 14, xmlEscape(sweepOrder[si]));
    double maxFrame = 0;
    for (const auto* c : configs) {
      double sum = 0;
      for (const auto& p : (*c)["passes"]) sum += p.value("median_ms", 0.0);
      maxFrame = std::max({maxFrame, sum, frameMedian(*c)});
    }
    if (maxFrame <= 0) maxFrame = 1;
    const double barTop = y0 + 24, barBottom = barTop + kChartH;
    svg += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{0}\" y2=\"{2:.1f}\" stroke=\"black\"/>\n"
        "<text x=\"5\" y=\"{3:.1f}\">{4:.3f} ms</text><text x=\"5\" y=\"{2:.1f}\">0</text>\n",
        kLeft, barTop, barBottom, barTop + 10, maxFrame);
    const double slot = plotW / double(configs.size());
    for (size_t ci = 0; ci < configs.size(); ++ci) {
      const auto& c = *configs[ci];
      double y = barBottom;
      const double x = kLeft + 5 + double(ci) * slot, w = std::max(2.0, slot * 0.7);
      for (const auto& p : c["passes"]) {
        const std::string name = p.value("name", "");
        const double h = p.value("median_ms", 0.0) / maxFrame * kChartH;
        const size_t colourIndex = size_t(std::find(passNames.begin(), passNames.end(), name) - passNames.begin());
        y -= h;
        svg += fmt::format(
            "<rect class=\"bar\" x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.2f}\" "
            "fill=\"{}\"><title>{} {}: {:.4f} ms</title></rect>\n",
            x, y, w, h, colour(colourIndex), xmlEscape(c.value("id", "")), xmlEscape(name), p.value("median_ms", 0.0));
      }
      svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" transform=\"rotate(30 {:.1f} {:.1f})\">{}</text>\n", x,
                         barBottom + 12, x, barBottom + 12, xmlEscape(axisValue(c)));
    }
    // Frame GPU median along the sweep's axis (configurations in plan order).
    if (configs.size() > 1) {
      const double lineTop = barBottom + 70, lineBottom = lineTop + kChartH - 40;
      svg += fmt::format(
          "<text x=\"10\" y=\"{:.1f}\" font-size=\"13\">sweep {}: frame GPU ms (median) vs {}</text>\n"
          "<line x1=\"{}\" y1=\"{:.1f}\" x2=\"{}\" y2=\"{:.1f}\" stroke=\"black\"/>\n"
          "<text x=\"5\" y=\"{:.1f}\">{:.3f} ms</text>\n",
          lineTop - 8, xmlEscape(sweepOrder[si]), xmlEscape(configs[0]->value("axis", "")), kLeft, lineTop, kLeft,
          lineBottom, lineTop + 10, maxFrame);
      std::string points;
      for (size_t ci = 0; ci < configs.size(); ++ci) {
        const double x = kLeft + 5 + (double(ci) + 0.35) * slot;
        const double y = lineBottom - frameMedian(*configs[ci]) / maxFrame * (lineBottom - lineTop);
        points += fmt::format("{:.1f},{:.1f} ", x, y);
        svg += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3\"><title>{}: {:.4f} ms</title></circle>\n", x, y,
                           xmlEscape(axisValue(*configs[ci])), frameMedian(*configs[ci]));
      }
      svg += fmt::format("<polyline class=\"sweep-line\" fill=\"none\" stroke=\"#333\" points=\"{}\"/>\n", points);
    }
    svg += "</g>\n";
  }
  // Legend: one swatch per pass.
  svg += "<g class=\"legend\">\n";
  for (size_t i = 0; i < passNames.size(); ++i)
    svg += fmt::format(
        "<rect x=\"{0:.0f}\" y=\"{1:.0f}\" width=\"12\" height=\"12\" fill=\"{2}\"/><text x=\"{3:.0f}\" "
        "y=\"{4:.0f}\">{5}</text>\n",
        kWidth, kTop + 14.0 * double(i), colour(i), kWidth + 16, kTop + 14.0 * double(i) + 10, xmlEscape(passNames[i]));
  svg += "</g>\n</svg>\n";
  return svg;
}

}  // namespace rayster::app
