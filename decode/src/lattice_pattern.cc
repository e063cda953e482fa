#include "lfsp/decode/lattice_pattern.h"

#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>

namespace lfsp::decode {

double RowAlternationRatio(const LightField& light_field) {
  const LightFieldShape& shape = light_field.shape();
  const int height = shape.height & ~1, width = shape.width;
  if (height < 16 || width < 4) return 0.0;
  cv::Mat grey(height, width, CV_64F);
  const ViewIndex centre = shape.Centre();
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double sum = 0.0;
      for (int c = 0; c < shape.channels; ++c) sum += light_field.at(centre, y, x, c);
      grey.at<double>(y, x) = sum / shape.channels;
    }
  grey -= cv::mean(grey)[0];
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      grey.at<double>(y, x) *= (0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * (y + 0.5) / height)) *
                               (0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * (x + 0.5) / width));
  cv::Mat spectrum;
  cv::dft(grey, spectrum, cv::DFT_COMPLEX_OUTPUT);
  auto row_energy = [&](int row) {
    double energy = 0.0;
    for (int x = 0; x < width; ++x) {
      const cv::Vec2d value = spectrum.at<cv::Vec2d>(row, x);
      energy += value[0] * value[0] + value[1] * value[1];
    }
    return energy;
  };
  double band = 0.0;
  int band_rows = 0;
  for (int row = 1; row < height; ++row) {
    const double frequency = std::abs((row <= height / 2 ? row : row - height) / static_cast<double>(height));
    if (frequency >= 0.40 && frequency <= 0.47) {
      band += row_energy(row);
      ++band_rows;
    }
  }
  if (band_rows == 0 || !(band > 0.0)) return 0.0;
  return row_energy(height / 2) / (band / band_rows);
}

}  // namespace lfsp::decode
