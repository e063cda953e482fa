#pragma once

// Sub-pixel checkerboard corners as the saddle point of the smoothed image.
//
// OpenCV's cornerSubPix weights each pixel's edge constraint by its squared gradient. On a sharp edge the gradient
// sits in the one or two pixels the edge crosses, so the estimate is pulled towards pixel centres and pixel borders
// (on simulated boards its positions came in steps of a quarter of a pixel, 0.07-0.10 px rms). A checker corner
// is point-symmetric about itself (I(c + r) = I(c - r) for two straight edges through c), so after any symmetric
// blur the image has a stationary point, a saddle, exactly at the corner. Fitting a quadratic to the blurred image
// around the estimate and moving to its stationary point, repeated until it stops moving, finds it without a
// pixel-grid bias.

#include <opencv2/core.hpp>
#include <vector>

namespace lfsp::calibrate {

// The blur for a board whose squares are `square_px` pixels wide: as wide as possible while the fitting window
// (about 2 sigma + 1 px each side) stays within the four squares around a corner.
double SaddleSigma(double square_px);

// Moves each corner to the saddle point of `grey` blurred by `sigma` near it. A corner whose neighbourhood has no
// saddle (it leaves the image, the fit is not a saddle, or the saddle is farther than the window) keeps its
// position. Returns how many corners were moved.
int RefineCornersAtSaddles(const cv::Mat& grey, std::vector<cv::Point2d>& corners, double sigma);

}  // namespace lfsp::calibrate
