#include "line_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace lfsp::noise_study {
namespace {

constexpr int kWidth = 720;
constexpr int kHeight = 440;
constexpr int kLeft = 80;
constexpr int kRight = 190;  // room for the legend
constexpr int kTop = 40;
constexpr int kBottom = 60;

const cv::Scalar kColours[] = {{31, 119, 180},  {255, 127, 14}, {44, 160, 44},   {214, 39, 40},
                               {148, 103, 189}, {140, 86, 75},  {227, 119, 194}, {127, 127, 127}};

std::string Tick(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

void Text(cv::Mat& image, const std::string& text, cv::Point at, double scale = 0.45) {
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(30, 30, 30), 1, cv::LINE_AA);
}

}  // namespace

cv::Mat LinePlot(const std::string& title, const std::string& x_label, const std::string& y_label,
                 const std::vector<double>& x, const std::vector<PlotSeries>& series) {
  cv::Mat image(kHeight, kWidth, CV_8UC3, cv::Scalar(255, 255, 255));
  double y_min = std::numeric_limits<double>::infinity();
  double y_max = -y_min;
  for (const auto& s : series)
    for (double value : s.y)
      if (std::isfinite(value)) {
        y_min = std::min(y_min, value);
        y_max = std::max(y_max, value);
      }
  if (!std::isfinite(y_min)) y_min = 0.0, y_max = 1.0;
  if (y_max - y_min < 1e-9) y_min -= 0.5, y_max += 0.5;
  const double pad = 0.05 * (y_max - y_min);
  y_min -= pad;
  y_max += pad;
  const double x_min = x.empty() ? 0.0 : *std::min_element(x.begin(), x.end());
  double x_max = x.empty() ? 1.0 : *std::max_element(x.begin(), x.end());
  if (x_max - x_min < 1e-12) x_max = x_min + 1.0;

  const int plot_w = kWidth - kLeft - kRight;
  const int plot_h = kHeight - kTop - kBottom;
  auto to_pixel = [&](double xv, double yv) {
    return cv::Point(kLeft + static_cast<int>(std::lround((xv - x_min) / (x_max - x_min) * plot_w)),
                     kTop + plot_h - static_cast<int>(std::lround((yv - y_min) / (y_max - y_min) * plot_h)));
  };

  cv::rectangle(image, {kLeft, kTop}, {kLeft + plot_w, kTop + plot_h}, cv::Scalar(120, 120, 120));
  for (int i = 0; i <= 4; ++i) {
    const double yv = y_min + (y_max - y_min) * i / 4.0;
    const cv::Point p = to_pixel(x_min, yv);
    cv::line(image, {kLeft, p.y}, {kLeft + plot_w, p.y}, cv::Scalar(230, 230, 230));
    Text(image, Tick(yv), {8, p.y + 4});
  }
  for (double xv : x) {
    const cv::Point p = to_pixel(xv, y_min);
    cv::line(image, {p.x, kTop + plot_h}, {p.x, kTop + plot_h + 5}, cv::Scalar(120, 120, 120));
    Text(image, Tick(xv), {p.x - 12, kTop + plot_h + 20});
  }
  Text(image, title, {kLeft, 25}, 0.6);
  Text(image, x_label, {kLeft + plot_w / 2 - 40, kHeight - 15});
  (void)y_label;  // the title names the plotted metric; a rotated axis label would need more than putText

  for (std::size_t k = 0; k < series.size(); ++k) {
    const cv::Scalar colour = kColours[k % (sizeof kColours / sizeof kColours[0])];
    cv::Point previous(-1, -1);
    for (std::size_t i = 0; i < x.size() && i < series[k].y.size(); ++i) {
      if (!std::isfinite(series[k].y[i])) {
        previous = {-1, -1};
        continue;
      }
      const cv::Point p = to_pixel(x[i], series[k].y[i]);
      if (previous.x >= 0) cv::line(image, previous, p, colour, 2, cv::LINE_AA);
      cv::circle(image, p, 4, colour, cv::FILLED, cv::LINE_AA);
      previous = p;
    }
    const int legend_y = kTop + 16 + static_cast<int>(k) * 22;
    cv::line(image, {kWidth - kRight + 15, legend_y - 4}, {kWidth - kRight + 40, legend_y - 4}, colour, 2);
    Text(image, series[k].name, {kWidth - kRight + 46, legend_y});
  }
  return image;  // colours above are given in RGB order: the image is RGB
}

}  // namespace lfsp::noise_study
