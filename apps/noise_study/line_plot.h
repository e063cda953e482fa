#pragma once

#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace lfsp::noise_study {

struct PlotSeries {
  std::string name;
  std::vector<double> y;  // one value per x; NaN = missing
};

// A line plot as an 8-bit RGB image: axes with ticks, one coloured line with markers per series, a legend.
// Drawn with OpenCV so the study needs no plotting package.
cv::Mat LinePlot(const std::string& title, const std::string& x_label, const std::string& y_label,
                 const std::vector<double>& x, const std::vector<PlotSeries>& series);

}  // namespace lfsp::noise_study
