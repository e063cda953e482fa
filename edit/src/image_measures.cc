#include "lfsp/edit/image_measures.h"

#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

#include "lfsp/core/error.h"

namespace lfsp::edit {
namespace {

void CheckMask(const cv::Mat& image, const cv::Mat& mask, const char* what) {
  if (!mask.empty() && (mask.type() != CV_8UC1 || mask.size() != image.size()))
    throw Error(std::string(what) + ": the mask must be CV_8UC1 of the image's size");
}

}  // namespace

double GradientEnergy(const cv::Mat& image, const cv::Mat& mask) {
  if (image.empty() || image.depth() != CV_32F) throw Error("gradient energy: expected a non-empty float image");
  CheckMask(image, mask, "gradient energy");
  const int channels = image.channels();
  double energy = 0.0;
  std::size_t count = 0;
  for (int y = 0; y + 1 < image.rows; ++y) {
    const float* row = image.ptr<float>(y);
    const float* below = image.ptr<float>(y + 1);
    const unsigned char* m = mask.empty() ? nullptr : mask.ptr<unsigned char>(y);
    for (int x = 0; x + 1 < image.cols; ++x) {
      if (m != nullptr && m[x] == 0) continue;
      for (int c = 0; c < channels; ++c) {
        const double gx = row[(x + 1) * channels + c] - row[x * channels + c];
        const double gy = below[x * channels + c] - row[x * channels + c];
        energy += gx * gx + gy * gy;
      }
      ++count;
    }
  }
  return count == 0 ? 0.0 : energy / (static_cast<double>(count) * channels);
}

double Psnr(const cv::Mat& reference, const cv::Mat& test, const cv::Mat& mask) {
  if (reference.empty() || reference.depth() != CV_32F || reference.size() != test.size() ||
      reference.type() != test.type())
    throw Error("PSNR: expected two non-empty float images of the same size and type");
  CheckMask(reference, mask, "PSNR");
  const int channels = reference.channels();
  double squared = 0.0;
  std::size_t count = 0;
  for (int y = 0; y < reference.rows; ++y) {
    const float* a = reference.ptr<float>(y);
    const float* b = test.ptr<float>(y);
    const unsigned char* m = mask.empty() ? nullptr : mask.ptr<unsigned char>(y);
    for (int x = 0; x < reference.cols; ++x) {
      if (m != nullptr && m[x] == 0) continue;
      for (int c = 0; c < channels; ++c) {
        const double e = static_cast<double>(a[x * channels + c]) - b[x * channels + c];
        squared += e * e;
      }
      ++count;
    }
  }
  if (count == 0) throw Error("PSNR: the mask selects no pixel");
  const double mse = squared / (static_cast<double>(count) * channels);
  if (mse == 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(1.0 / mse);
}

}  // namespace lfsp::edit
