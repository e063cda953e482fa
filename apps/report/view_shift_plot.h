#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace lfsp::report {

// Whether a metrics value is a per-view list of shifts: an array of objects with "u", "v", "dx" and "dy" (the
// decode's registration on the ideal light field, decode_vs_truth.registration.views).
bool IsViewShiftList(const nlohmann::ordered_json& value);

// The list drawn as an inline SVG plot: one cell per view (u across, v down), an arrow from its centre showing the
// view's shift (dx, dy) (half a cell long for the largest), the cell's colour its length (white: none, orange-red:
// the largest); views missing from the list are grey. Hovering a cell gives its numbers.
std::string ViewShiftPlotSvg(const nlohmann::ordered_json& views);

}  // namespace lfsp::report
