#pragma once

// Choosing light-field superpixels in the centre view. Each function returns sorted, distinct label ids.

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>
#include <string>
#include <vector>

#include "lfsp/core/light_field.h"

namespace lfsp::edit {

// The ids as given, sorted and deduplicated. Throws lfsp::Error if an id is negative or occurs in no ray.
std::vector<std::int32_t> SelectLabelIds(const Labels& labels, const std::vector<std::int32_t>& ids);

// A centre-view pixel written "x,y" (column,row, integers). Throws lfsp::Error naming `option` otherwise (1e20,
// nan, 3.5 and trailing text are refused here, not cast).
cv::Point ParseViewPoint(const std::string& text, const std::string& option);

// Throws lfsp::Error naming the point when one lies outside a centre view of width x height: commands check this
// before any work, SelectAtPoints again on the labels.
void RequirePointsInside(const std::vector<cv::Point>& points, int width, int height);

// The label under each point (x = column, y = row) of the centre view. Throws lfsp::Error if a point lies outside
// the view or on an unlabelled ray.
std::vector<std::int32_t> SelectAtPoints(const Labels& labels, const std::vector<cv::Point>& points);

// The labels that cover more than `min_fraction` of their centre-view area inside `mask`, a centre-view image
// (any depth, first channel used; "inside" = above half the type's maximum for integers, above 0.5 for floats).
// Throws lfsp::Error if the mask's size differs from the view size or the selection is empty.
std::vector<std::int32_t> SelectByMask(const Labels& labels, const cv::Mat& mask, double min_fraction = 0.5);

}  // namespace lfsp::edit
