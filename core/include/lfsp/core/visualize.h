#pragma once

#include <opencv2/core/mat.hpp>
#include <optional>
#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/core/metadata.h"

namespace lfsp {

// Pictures for people: previews, reports and overlays. All return 8-bit RGB (CV_8UC3) unless said otherwise.

// A float image (any channels) ready for an 8/16-bit preview: a copy clamped to [0, 1], sRGB-encoded if the data
// are linear (IEC 61966-2-1 curve).
cv::Mat DisplayEncoded(const cv::Mat& image, Transfer transfer);

// A view (CV_32FC1/3 in [0, 1]) for display: DisplayEncoded, then 8-bit RGB.
cv::Mat DisplayRgb8(const cv::Mat& view, Transfer transfer);

// Disparity colour-mapped with OpenCV's TURBO map over `range` (default: the map's finite min..max);
// non-finite values are black.
cv::Mat ColourMapDisparity(const DisparityMap& disparity, std::optional<DisparityRange> range = std::nullopt);

// Epipolar-plane images. Horizontal: row y of views (u, v) for u = 0..nu-1 -> nu x W image (row = u).
// Vertical: column x of views (u, v) for v = 0..nv-1 -> H x nv image (column = v), i.e. transposed so that
// the spatial axis stays vertical like in the view itself.
// The views along the middle row, left to right, then down the middle column, top to bottom, as 8-bit RGB: the
// frames of a view-sweep animation (the report's, `lfsp convert LF sweep.gif`).
std::vector<cv::Mat> ViewSweepFrames(const LightField& light_field);

cv::Mat HorizontalEpi(const LightField& light_field, int y, int v);
cv::Mat VerticalEpi(const LightField& light_field, int x, int u);
cv::Mat HorizontalEpi(const Labels& labels, int y, int v);  // CV_32SC1
cv::Mat VerticalEpi(const Labels& labels, int x, int u);    // CV_32SC1

// Marks every pixel whose right or lower neighbour has another label (CV_32SC1 `labels`) in `colour` (RGB).
cv::Mat DrawLabelBoundaries(const cv::Mat& rgb8, const cv::Mat& labels, cv::Vec3b colour = {255, 40, 40});

// Nearest-neighbour enlargement by an integer factor per axis (thin EPIs are unreadable at 1:1).
cv::Mat Enlarge(const cv::Mat& image, int factor_x, int factor_y);

// Pictures of a segmentation, encoded for display per the light field's transfer, with DrawLabelBoundaries: the
// centre view; the horizontal EPI of the middle view row at image row `y` (one row per view, u down); the vertical
// EPI of the middle view column at image column `x` (v across). EPIs are stretched across the views by `stretch`
// (0: DefaultEpiStretch) so that a handful of views makes a readable picture. Throws lfsp::Error if the labels'
// shape is not the light field's or the row/column is outside the views.
cv::Mat CentreViewBoundaries(const LightField& light_field, const Labels& labels);
cv::Mat HorizontalEpiBoundaries(const LightField& light_field, const Labels& labels, int y, int stretch = 0);
cv::Mat VerticalEpiBoundaries(const LightField& light_field, const Labels& labels, int x, int stretch = 0);

// About 96 pixels across the views, at least 4 per view.
int DefaultEpiStretch(const LightFieldShape& shape);

}  // namespace lfsp
