#pragma once
// Reports of `rayster bench` results: CSV (one row per configuration and pass) and an SVG of
// per-pass stacked bars per sweep plus, for sweeps of several configurations, the frame time
// along the sweep's axis. Plain text both, written by our own code.
#include <string>

#include <nlohmann/json.hpp>

namespace rayster::app {

// Columns: id,sweep,axis,x,scene,width,height,mode,primary,max_depth,pass,median_ms,p95_ms,min_ms,
// rays,grays_per_s. The per-frame GPU sum comes as pass "frame".
std::string benchCsv(const nlohmann::json& results);
std::string benchSvg(const nlohmann::json& results);
// The value of a configuration on its sweep's axis, as plotted (e.g. "1920x1080", "lights 16").
std::string axisValue(const nlohmann::json& config);

}  // namespace rayster::app
