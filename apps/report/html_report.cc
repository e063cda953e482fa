#include "html_report.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "metric_descriptions.h"
#include "view_shift_plot.h"

namespace lfsp::report {
namespace {

std::string Base64(const std::vector<unsigned char>& bytes) {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned value = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    out += kAlphabet[(value >> 18) & 63];
    out += kAlphabet[(value >> 12) & 63];
    out += kAlphabet[(value >> 6) & 63];
    out += kAlphabet[value & 63];
  }
  if (i < bytes.size()) {
    const unsigned value = (bytes[i] << 16) | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0);
    out += kAlphabet[(value >> 18) & 63];
    out += kAlphabet[(value >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(value >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string Escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string FormatValue(const nlohmann::ordered_json& value) {
  if (value.is_number_float()) {
    std::ostringstream text;
    text.precision(4);
    text << value.get<double>();
    return text.str();
  }
  if (value.is_string()) return value.get<std::string>();
  return value.dump();
}

std::string_view LastPart(std::string_view key) {
  const std::size_t dot = key.find('.');
  return dot == std::string_view::npos ? key : key.substr(dot + 1);
}

// The words a reader sees for a key: its description's name, with where it was measured ("near depth edges").
std::string MetricName(const std::string& key, const MetricDescription* description) {
  std::string name(description != nullptr ? description->name : LastPart(key));
  std::size_t start = 0;
  while (start < key.size()) {
    const std::size_t end = std::min(key.find('.', start), key.size());
    const std::string_view region = DescribeRegion(std::string_view(key).substr(start, end - start));
    if (!region.empty()) name += " (" + std::string(region) + ")";
    start = end + 1;
  }
  return name;
}

const char* BetterText(Better better) {
  switch (better) {
    case Better::kHigher:
      return "&#8593; higher";
    case Better::kLower:
      return "&#8595; lower";
    default:
      return "";
  }
}

// A per-view list drawn as a plot under its group's table.
struct Plot {
  std::string key;
  std::string svg;
};

// One row per figure of a group of metrics (nested keys joined with dots): name in words and raw key, value with its
// unit, which way is better, meaning, source. Per-view lists become plots.
void AppendMetricRows(const nlohmann::ordered_json& value, const std::string& key, std::ostringstream& html,
                      std::vector<Plot>& plots) {
  if (value.is_object()) {
    for (const auto& [child_key, child] : value.items()) AppendMetricRows(child, key + "." + child_key, html, plots);
    return;
  }
  if (IsViewShiftList(value)) {
    plots.push_back({key, ViewShiftPlotSvg(value)});
    return;
  }
  const MetricDescription* description = DescribeMetric(key);
  std::string shown = value.is_null() ? std::string("n/a") : FormatValue(value);
  if (value.is_array()) shown = "a list of " + std::to_string(value.size()) + " (in the raw JSON)";
  if (description != nullptr && !description->unit.empty() && value.is_number())
    shown += " " + std::string(description->unit);
  // A figure the table does not describe yet is marked, so that a test can find it.
  html << (description != nullptr ? "<tr>" : "<tr class=\"undescribed\">") << "<td>"
       << Escape(MetricName(key, description)) << "<br><code class=\"key\">" << Escape(key)
       << "</code></td><td class=\"value\">" << Escape(shown) << "</td><td>"
       << (description != nullptr ? BetterText(description->better) : "") << "</td><td>"
       << (description != nullptr ? Escape(std::string(description->meaning)) : "") << "</td><td class=\"source\">"
       << (description == nullptr        ? ""
           : description->source.empty() ? "lfsp"
                                         : Escape(std::string(description->source)))
       << "</td></tr>\n";
}

void AppendMetrics(const Report& report, std::ostringstream& html) {
  html << "<section><h2>Metrics</h2>\n";
  if (!report.raw_json.empty())
    html << "<p class=\"note\">Each figure's key is shown in grey; every figure, unrounded, is in <a href=\""
         << Escape(report.raw_json) << "\">" << Escape(report.raw_json) << "</a> under \"metrics\".</p>\n";
  for (const auto& [group, values] : report.metrics.items()) {
    const std::string_view title = DescribeGroup(group);
    html << "<h3>" << Escape(title.empty() ? group : std::string(title)) << "</h3>\n<table class=\"metrics\"><tr>"
         << "<th>Figure</th><th>Value</th><th>Better</th><th>Meaning</th><th>Source</th></tr>\n";
    std::vector<Plot> plots;
    AppendMetricRows(values, group, html, plots);
    html << "</table>\n";
    for (const Plot& plot : plots) {
      const MetricDescription* description = DescribeMetric(plot.key);
      html << "<figure>" << plot.svg << "<figcaption><b>" << Escape(MetricName(plot.key, description)) << "</b> "
           << (description != nullptr ? Escape(std::string(description->meaning)) : "")
           << ". Hover a view for its numbers. <code class=\"key\">" << Escape(plot.key)
           << "</code></figcaption></figure>\n";
    }
  }
  html << "</section>\n";
}

// A nested JSON object as a two-column table, nested keys joined with dots.
void AppendRows(const nlohmann::ordered_json& value, const std::string& prefix, std::ostringstream& html) {
  if (value.is_object()) {
    for (const auto& [key, child] : value.items()) AppendRows(child, prefix.empty() ? key : prefix + "." + key, html);
    return;
  }
  html << "<tr><td>" << Escape(prefix) << "</td><td>" << Escape(FormatValue(value)) << "</td></tr>\n";
}

constexpr const char* kStyle = R"(
body { font-family: sans-serif; margin: 2em auto; max-width: 1200px; color: #222; background: #fafafa; }
h1 { margin-bottom: 0.2em; } .subtitle { color: #666; margin-top: 0; }
section { background: #fff; border: 1px solid #ddd; border-radius: 6px; padding: 1em 1.5em; margin: 1.5em 0; }
.figures { display: flex; flex-wrap: wrap; gap: 1.2em; }
figure { margin: 0; max-width: 100%; }
figure img { max-width: 100%; min-width: 192px; image-rendering: pixelated; border: 1px solid #ccc; display: block; }
figcaption { font-size: 0.85em; color: #555; max-width: 560px; }
table { border-collapse: collapse; margin: 0.5em 0 1em 0; }
td, th { border: 1px solid #ddd; padding: 0.25em 0.7em; text-align: left; font-size: 0.9em; }
td.value { font-family: monospace; white-space: nowrap; }
table.metrics td { vertical-align: top; } table.metrics td:nth-child(3) { white-space: nowrap; } table.metrics td.source { color: #555; font-size: 0.8em; }
code.key { color: #888; font-size: 0.8em; } .note { color: #555; font-size: 0.9em; }
table.timings td:last-child { font-family: monospace; }
svg.plot { border: 1px solid #ccc; background: #fff; display: block; }
)";

constexpr const char* kAnimationScript = R"(
document.querySelectorAll('img[data-frames]').forEach(function (img) {
  var frames = JSON.parse(img.getAttribute('data-frames'));
  var i = 0, step = 1;
  setInterval(function () {
    if (i + step < 0 || i + step >= frames.length) step = -step;
    i += step;
    img.src = frames[i];
  }, 1000 / parseFloat(img.getAttribute('data-fps')));
});
)";

}  // namespace

std::string PngDataUri(const cv::Mat& rgb) {
  cv::Mat bgr8;
  cv::Mat converted = rgb;
  if (rgb.depth() != CV_8U) rgb.convertTo(converted, CV_8U, 255.0);
  if (converted.channels() == 3) {
    cv::cvtColor(converted, bgr8, cv::COLOR_RGB2BGR);
  } else {
    bgr8 = converted;
  }
  std::vector<unsigned char> png;
  cv::imencode(".png", bgr8, png);
  return "data:image/png;base64," + Base64(png);
}

std::string RenderHtml(const Report& report) {
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" << Escape(report.title)
       << "</title>\n<style>" << kStyle << "</style></head><body>\n";
  html << "<h1>" << Escape(report.title) << "</h1>\n<p class=\"subtitle\">" << Escape(report.subtitle) << "</p>\n";
  for (const Section& section : report.sections) {
    html << "<section><h2>" << Escape(section.title) << "</h2><div class=\"figures\">\n";
    for (const Figure& figure : section.figures) {
      html << "<figure><img alt=\"" << Escape(figure.title) << "\" src=\"" << PngDataUri(figure.image)
           << "\"><figcaption><b>" << Escape(figure.title) << "</b> " << Escape(figure.caption)
           << "</figcaption></figure>\n";
    }
    for (const Animation& animation : section.animations) {
      if (animation.frames.empty()) continue;
      nlohmann::json frames = nlohmann::json::array();
      for (const cv::Mat& frame : animation.frames) frames.push_back(PngDataUri(frame));
      html << "<figure><img alt=\"" << Escape(animation.title) << "\" src=\"" << frames[0].get<std::string>()
           << "\" data-fps=\"" << animation.frames_per_second << "\" data-frames='" << frames.dump()
           << "'><figcaption><b>" << Escape(animation.title) << "</b> " << Escape(animation.caption)
           << "</figcaption></figure>\n";
    }
    html << "</div></section>\n";
  }
  if (!report.metrics.empty()) AppendMetrics(report, html);
  if (!report.timings.empty()) {
    html << "<section><h2>Timings (wall seconds)</h2><table class=\"timings\">\n";
    AppendRows(report.timings, "", html);
    html << "</table></section>\n";
  }
  html << "<script>" << kAnimationScript << "</script>\n</body></html>\n";
  return html.str();
}

}  // namespace lfsp::report
