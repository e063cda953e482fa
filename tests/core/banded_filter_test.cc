// Unit tests of lfsp/core/banded_filter.h: SeparableFilterInBands must give cv::sepFilter2D's bytes, because the JPEG
// mosaic restoration, whose decoded views are compared byte for byte across changes, filters with it.

#include <gtest/gtest.h>

#include <cstring>
#include <opencv2/imgproc.hpp>

#include "lfsp/core/banded_filter.h"
#include "lfsp/core/error.h"

namespace lfsp {
namespace {

bool SameBytes(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return false;
  for (int y = 0; y < a.rows; ++y)
    if (std::memcmp(a.ptr(y), b.ptr(y), a.cols * a.elemSize()) != 0) return false;
  return true;
}

cv::Mat Noise(int rows, int cols, int type, int seed) {
  cv::Mat image(rows, cols, type);
  cv::RNG random(static_cast<std::uint64_t>(seed));
  random.fill(image, cv::RNG::UNIFORM, 0.0, 255.0);
  return image;
}

TEST(SeparableFilterInBands, GivesTheWholeImageFilterByteForByte) {
  int seed = 1000;
  // Symmetric and lopsided kernels of 3 to 13 taps, different across and down; a region of a larger image too.
  const cv::Mat parent = Noise(900, 700, CV_32FC1, 98);
  for (const cv::Mat& image :
       {Noise(5, 7, CV_32FC1, seed++), Noise(378, 377, CV_32FC1, seed++), Noise(1643, 1640, CV_32FC1, seed++),
        Noise(640, 1001, CV_32FC3, seed++), parent(cv::Rect(13, 101, 600, 700))})
    for (const double sigma : {0.5, 0.85, 2.0})
      for (const int border : {cv::BORDER_REFLECT, cv::BORDER_REFLECT_101, cv::BORDER_REPLICATE}) {
        const cv::Mat across = cv::getGaussianKernel(2 * static_cast<int>(3 * sigma) + 1, sigma, CV_32F);
        const cv::Mat down = (cv::Mat_<float>(3, 1) << 0.2f, 0.5f, 0.3f);
        cv::Mat whole, banded;
        cv::sepFilter2D(image, whole, CV_32F, across, down, cv::Point(-1, -1), 0.0, border);
        SeparableFilterInBands(image, banded, across, down, border);
        EXPECT_TRUE(SameBytes(whole, banded)) << image.size() << " sigma " << sigma << " border " << border;
      }
}

TEST(SeparableFilterInBands, RefusesToWorkInPlaceOrOnIntegers) {
  cv::Mat image = Noise(200, 100, CV_32FC1, 6), out;
  const cv::Mat kernel = cv::getGaussianKernel(5, 1.0, CV_32F);
  EXPECT_THROW(SeparableFilterInBands(image, image, kernel, kernel, cv::BORDER_REFLECT), Error);
  cv::Mat bytes(200, 100, CV_8UC1, cv::Scalar(3));
  EXPECT_THROW(SeparableFilterInBands(bytes, out, kernel, kernel, cv::BORDER_REFLECT), Error);
  EXPECT_THROW(SeparableFilterInBands(image, out, cv::getGaussianKernel(5, 1.0, CV_64F), kernel, cv::BORDER_REFLECT),
               Error);
  EXPECT_THROW(SeparableFilterInBands(image, out, cv::Mat(3, 3, CV_32FC1, cv::Scalar(0.1)), kernel, cv::BORDER_REFLECT),
               Error);
}

}  // namespace
}  // namespace lfsp
