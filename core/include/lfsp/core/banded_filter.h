#pragma once

#include <opencv2/core/mat.hpp>

namespace lfsp {

// cv::sepFilter2D of a float image with float kernels (each a CV_32F column or row), the same bytes, on every OpenMP
// thread. OpenCV runs a float image's separable filters (sepFilter2D, GaussianBlur) on one thread; here each thread
// filters horizontal bands of rows, each band read as a region of `source`, so OpenCV takes the rows above and below it
// from the image itself, as the whole call would, and borders only at the image's own edges
// (tests/core/banded_filter_test.cc compares every byte). A 3280 x 3280 Gaussian at sigma 1 took 20.5 ms and takes 10
// on two cores. `destination` must not share memory with `source` (a band would read rows that another band has
// written); it is allocated unless it already has the size and type. Called inside a parallel region, it runs on the
// calling thread alone. lfsp::Error for other images or kernels.
void SeparableFilterInBands(const cv::Mat& source, cv::Mat& destination, const cv::Mat& kernel_x,
                            const cv::Mat& kernel_y, int border);

}  // namespace lfsp
