// Unit tests of lfsp/core/banded_filter.h: GaussianBlurInBands and SeparableFilterInBands must give cv::GaussianBlur's
// and cv::sepFilter2D's bytes, because the JPEG mosaic restoration, whose decoded views are compared byte for byte
// across changes, filters with them.

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

TEST(GaussianBlurInBands, GivesTheWholeImageBlurByteForByte) {
  int seed = 1;
  // Sizes below, at and well above the band height, odd widths, one to three channels; kernels from 3 to 25 taps.
  for (const cv::Size size : {cv::Size(7, 5), cv::Size(377, 378), cv::Size(1001, 640), cv::Size(1640, 1643)})
    for (const int type : {CV_32FC1, CV_32FC3})
      for (const double sigma : {0.6, 1.0, 2.5, 4.0})
        for (const int border : {cv::BORDER_REFLECT, cv::BORDER_REFLECT_101, cv::BORDER_REPLICATE}) {
          const cv::Mat image = Noise(size.height, size.width, type, seed++);
          cv::Mat whole, banded;
          cv::GaussianBlur(image, whole, cv::Size(), sigma, 0.5 * sigma, border);
          GaussianBlurInBands(image, banded, sigma, 0.5 * sigma, border);
          EXPECT_TRUE(SameBytes(whole, banded))
              << size << " type " << type << " sigma " << sigma << " border " << border;
        }
}

TEST(GaussianBlurInBands, ReadsARegionsNeighbouringRowsAsOpenCvDoes) {
  // A region of a larger image: OpenCV takes the rows and columns around it from the image, not from a border rule.
  const cv::Mat parent = Noise(900, 700, CV_32FC1, 99);
  const cv::Mat region = parent(cv::Rect(13, 101, 600, 700));
  cv::Mat whole, banded;
  cv::GaussianBlur(region, whole, cv::Size(), 1.0, 1.0, cv::BORDER_REFLECT);
  GaussianBlurInBands(region, banded, 1.0, 1.0, cv::BORDER_REFLECT);
  EXPECT_TRUE(SameBytes(whole, banded));
}

TEST(GaussianBlurInBands, RefusesToWorkInPlaceOrOnIntegers) {
  cv::Mat image = Noise(200, 100, CV_32FC1, 5);
  EXPECT_THROW(GaussianBlurInBands(image, image, 1.0, 1.0, cv::BORDER_REFLECT), Error);
  cv::Mat bytes(200, 100, CV_8UC1, cv::Scalar(3)), out;
  EXPECT_THROW(GaussianBlurInBands(bytes, out, 1.0, 1.0, cv::BORDER_REFLECT), Error);
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
}

}  // namespace
}  // namespace lfsp
