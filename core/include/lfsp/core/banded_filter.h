#pragma once

#include <opencv2/core/mat.hpp>

namespace lfsp {

// cv::GaussianBlur of a float image, the same bytes, on every OpenMP thread. OpenCV runs a float image's separable
// filter on one thread; here each thread filters horizontal bands of rows, each band read as a region of `source`, so
// OpenCV takes the rows above and below it from the image itself, as the whole call would, and borders only at the
// image's own edges (tests/core/banded_filter_test.cc compares every byte). A 3280 x 3280 blur at sigma 1 took 20.5 ms
// and takes 10 on two cores. `destination` must not share memory with `source` (a band would read rows that another
// band has written); it is allocated unless it already has the size and type. Called inside a parallel region, it
// runs on the calling thread alone.
void GaussianBlurInBands(const cv::Mat& source, cv::Mat& destination, double sigma_x, double sigma_y, int border);

// cv::sepFilter2D of a float image with float kernels (CV_32F columns or rows), the same bytes, in bands as above and
// under the same conditions.
void SeparableFilterInBands(const cv::Mat& source, cv::Mat& destination, const cv::Mat& kernel_x,
                            const cv::Mat& kernel_y, int border);

}  // namespace lfsp
