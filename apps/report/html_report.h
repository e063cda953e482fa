#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace lfsp::report {

// A figure of the report. Images are RGB (float in [0, 1] or 8-bit), embedded as PNG data URIs so the HTML file is
// self-contained.
struct Figure {
  std::string title;
  std::string caption;
  cv::Mat image;
};

// A sequence of frames shown as a looping animation (e.g. a sweep through the views) with a small script.
struct Animation {
  std::string title;
  std::string caption;
  std::vector<cv::Mat> frames;
  int frames_per_second = 8;
};

struct Section {
  std::string title;
  std::vector<Figure> figures;
  std::vector<Animation> animations;
};

struct Report {
  std::string title;
  std::string subtitle;
  std::vector<Section> sections;
  nlohmann::ordered_json metrics;  // shown as tables, one per top-level key, described (metric_descriptions.h)
  nlohmann::ordered_json timings;  // stage -> seconds
  std::string raw_json;            // where the raw figures are, relative to the report (e.g. "summary.json"), or ""
};

// The whole report as one HTML document (no external files, no network).
std::string RenderHtml(const Report& report);

// PNG bytes of an RGB image as a data URI ("data:image/png;base64,...").
std::string PngDataUri(const cv::Mat& rgb);

}  // namespace lfsp::report
