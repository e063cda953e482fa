#include "view_shift_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <utility>

namespace lfsp::report {
namespace {

constexpr int kCell = 30;           // pixels per view
constexpr int kMargin = 28;         // room for the axis labels
constexpr double kMinScale = 0.01;  // px that an arrow half a cell long stands for, at least

std::string Number(double value, const char* format = "%.3f") {
  char text[32];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

// A cell's background by the fraction of the plot's scale its shift is: white for none through to orange-red.
std::string Fill(double fraction) {
  const double f = std::clamp(fraction, 0.0, 1.0);
  const int green = static_cast<int>(std::lround(255 - 150 * f));
  const int blue = static_cast<int>(std::lround(255 - 215 * f));
  return "rgb(255," + std::to_string(green) + "," + std::to_string(blue) + ")";
}

// A line from (x1, y1) to (x2, y2) with a filled head at (x2, y2).
std::string Arrow(double x1, double y1, double x2, double y2, const std::string& colour) {
  const double length = std::hypot(x2 - x1, y2 - y1);
  const double ux = (x2 - x1) / length, uy = (y2 - y1) / length;
  const double head = std::min(4.0, length / 2.0), half_width = head * 0.6;
  const double bx = x2 - ux * head, by = y2 - uy * head;
  std::ostringstream svg;
  svg << "<line x1=\"" << Number(x1, "%.1f") << "\" y1=\"" << Number(y1, "%.1f") << "\" x2=\"" << Number(bx, "%.1f")
      << "\" y2=\"" << Number(by, "%.1f") << "\" stroke=\"" << colour << "\" stroke-width=\"2\"/>"
      << "<polygon points=\"" << Number(x2, "%.1f") << "," << Number(y2, "%.1f") << " "
      << Number(bx - uy * half_width, "%.1f") << "," << Number(by + ux * half_width, "%.1f") << " "
      << Number(bx + uy * half_width, "%.1f") << "," << Number(by - ux * half_width, "%.1f") << "\" fill=\"" << colour
      << "\"/>";
  return svg.str();
}

}  // namespace

bool IsViewShiftList(const nlohmann::ordered_json& value) {
  if (!value.is_array() || value.empty()) return false;
  for (const auto& entry : value)
    if (!entry.is_object() || !entry.contains("u") || !entry.contains("v") || !entry.contains("dx") ||
        !entry.contains("dy"))
      return false;
  return true;
}

std::string ViewShiftPlotSvg(const nlohmann::ordered_json& views) {
  int nu = 0, nv = 0;
  double largest = 0.0;
  std::map<std::pair<int, int>, std::pair<double, double>> shifts;
  for (const auto& entry : views) {
    const int u = entry["u"].get<int>(), v = entry["v"].get<int>();
    const double dx = entry["dx"].get<double>(), dy = entry["dy"].get<double>();
    nu = std::max(nu, u + 1);
    nv = std::max(nv, v + 1);
    shifts[{u, v}] = {dx, dy};
    largest = std::max(largest, std::hypot(dx, dy));
  }
  // The largest shift, rounded up to hundredths of a pixel: the longest arrow fills its half cell.
  const double scale = std::max(kMinScale, std::ceil(largest * 100.0) / 100.0);

  const int width = std::max(2 * kMargin + nu * kCell, 300), height = 2 * kMargin + nv * kCell;
  std::ostringstream svg;
  svg << "<svg class=\"plot\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << " " << height << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
      << "<text x=\"" << kMargin + nu * kCell / 2 << "\" y=\"16\" text-anchor=\"middle\">view u &#8594;</text>\n"
      << "<text x=\"12\" y=\"" << kMargin + nv * kCell / 2 << "\" text-anchor=\"middle\" transform=\"rotate(-90 12 "
      << kMargin + nv * kCell / 2 << ")\">view v &#8595;</text>\n";
  for (int v = 0; v < nv; ++v) {
    for (int u = 0; u < nu; ++u) {
      const int x = kMargin + u * kCell, y = kMargin + v * kCell;
      const auto found = shifts.find({u, v});
      if (found == shifts.end()) {
        svg << "<rect x=\"" << x << "\" y=\"" << y << "\" width=\"" << kCell << "\" height=\"" << kCell
            << "\" fill=\"#ddd\" stroke=\"#fff\"><title>view (" << u << ", " << v
            << "): not registered (too dim)</title></rect>\n";
        continue;
      }
      const auto [dx, dy] = found->second;
      const double length = std::hypot(dx, dy);
      const double cx = x + kCell / 2.0, cy = y + kCell / 2.0;
      const double k = (kCell / 2.0 - 2.0) / scale;
      svg << "<g><title>view (" << u << ", " << v << "): dx " << Number(dx) << " px, dy " << Number(dy)
          << " px, |shift| " << Number(length) << " px</title>"
          << "<rect x=\"" << x << "\" y=\"" << y << "\" width=\"" << kCell << "\" height=\"" << kCell << "\" fill=\""
          << Fill(length / scale) << "\" stroke=\"#fff\"/>"
          << "<circle cx=\"" << cx << "\" cy=\"" << cy << "\" r=\"1.5\" fill=\"#888\"/>";
      if (length * k >= 1.0) svg << Arrow(cx, cy, cx + dx * k, cy + dy * k, "#333");
      svg << "</g>\n";
    }
  }
  svg << "<text x=\"" << kMargin << "\" y=\"" << height - 8
      << "\">arrow half a cell long, or the reddest cell = " << Number(scale, "%.2f") << " px</text>\n</svg>";
  return svg.str();
}

}  // namespace lfsp::report
