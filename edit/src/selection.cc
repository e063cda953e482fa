#include "lfsp/edit/selection.h"

#include <algorithm>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "lfsp/core/error.h"

namespace lfsp::edit {
namespace {

std::vector<std::int32_t> SortedUnique(std::vector<std::int32_t> ids) {
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

void CheckLabels(const Labels& labels) {
  if (labels.empty()) throw Error("selection: the labels are empty");
}

}  // namespace

std::vector<std::int32_t> SelectLabelIds(const Labels& labels, const std::vector<std::int32_t>& ids) {
  CheckLabels(labels);
  std::vector<std::int32_t> selection = SortedUnique(ids);
  if (selection.empty()) throw Error(OptionName("label_ids") + ": no label id given");
  if (selection.front() < 0)
    throw Error(OptionName("label_ids") + ": label ids are >= 0, got " + std::to_string(selection.front()));
  std::vector<bool> present(selection.size(), false);
  const std::int32_t* data = labels.data();
  const std::size_t count = labels.size();
  for (std::size_t i = 0; i < count; ++i) {
    const auto it = std::lower_bound(selection.begin(), selection.end(), data[i]);
    if (it != selection.end() && *it == data[i]) present[static_cast<std::size_t>(it - selection.begin())] = true;
  }
  for (std::size_t k = 0; k < selection.size(); ++k)
    if (!present[k])
      throw Error(OptionName("label_ids") + ": label " + std::to_string(selection[k]) + " occurs in no ray");
  return selection;
}

cv::Point ParseViewPoint(const std::string& text, const std::string& option) {
  const std::size_t comma = text.find(',');
  try {
    if (comma == std::string::npos) throw std::invalid_argument("no comma");
    std::size_t used_x = 0;
    std::size_t used_y = 0;
    const int x = std::stoi(text.substr(0, comma), &used_x);
    const int y = std::stoi(text.substr(comma + 1), &used_y);
    if (used_x != comma || used_y != text.size() - comma - 1) throw std::invalid_argument("trailing characters");
    return {x, y};
  } catch (const std::exception&) {
    throw Error(option + " '" + text + "': expected a centre-view pixel as x,y (column,row, integers), e.g. 120,88");
  }
}

void RequirePointsInside(const std::vector<cv::Point>& points, int width, int height) {
  for (const cv::Point& point : points)
    if (point.x < 0 || point.y < 0 || point.x >= width || point.y >= height)
      throw Error(OptionName("at") + " " + std::to_string(point.x) + "," + std::to_string(point.y) +
                  ": outside the centre view (" + std::to_string(width) + "x" + std::to_string(height) + ")");
}

std::vector<std::int32_t> SelectAtPoints(const Labels& labels, const std::vector<cv::Point>& points) {
  CheckLabels(labels);
  if (points.empty()) throw Error(OptionName("at") + ": no point given");
  const LightFieldShape& shape = labels.shape();
  const ViewIndex centre = shape.Centre();
  RequirePointsInside(points, shape.width, shape.height);
  std::vector<std::int32_t> selection;
  for (const cv::Point& point : points) {
    const std::string where = OptionName("at") + " " + std::to_string(point.x) + "," + std::to_string(point.y);
    const std::int32_t label = labels.at(centre, point.y, point.x);
    if (label < 0) throw Error(where + ": the centre-view ray there is unlabelled");
    selection.push_back(label);
  }
  return SortedUnique(selection);
}

namespace {

// "Inside" per mask pixel: above half the maximum of the mask's type (0.5 for floats), first channel.
cv::Mat BinaryMask(const cv::Mat& mask) {
  cv::Mat first;
  cv::extractChannel(mask, first, 0);
  double threshold = 0.5;
  switch (first.depth()) {
    case CV_8U:
      threshold = 127.5;
      break;
    case CV_16U:
      threshold = 32767.5;
      break;
    case CV_32F:
    case CV_64F:
      threshold = 0.5;
      break;
    default:
      throw Error(OptionName("mask") + ": unsupported mask sample type");
  }
  cv::Mat first64;
  first.convertTo(first64, CV_64F);
  return first64 > threshold;  // CV_8UC1, 255 inside
}

}  // namespace

std::vector<std::int32_t> SelectByMask(const Labels& labels, const cv::Mat& mask, double min_fraction) {
  CheckLabels(labels);
  const LightFieldShape& shape = labels.shape();
  if (mask.empty() || mask.cols != shape.width || mask.rows != shape.height)
    throw Error(OptionName("mask") + ": the mask is " + std::to_string(mask.cols) + "x" + std::to_string(mask.rows) +
                " but the centre view is " + std::to_string(shape.width) + "x" + std::to_string(shape.height));
  if (!(min_fraction >= 0.0 && min_fraction < 1.0))
    throw Error(OptionName("mask") + ": the area fraction must be in [0, 1), got " + std::to_string(min_fraction));
  const cv::Mat inside = BinaryMask(mask);
  const cv::Mat centre = labels.View(shape.Centre());

  struct Area {
    std::size_t total = 0;
    std::size_t inside = 0;
  };
  std::unordered_map<std::int32_t, Area> areas;
  for (int y = 0; y < shape.height; ++y) {
    const std::int32_t* row = centre.ptr<std::int32_t>(y);
    const unsigned char* m = inside.ptr<unsigned char>(y);
    for (int x = 0; x < shape.width; ++x) {
      if (row[x] < 0) continue;
      Area& area = areas[row[x]];
      ++area.total;
      if (m[x] != 0) ++area.inside;
    }
  }
  std::vector<std::int32_t> selection;
  for (const auto& [label, area] : areas)
    if (static_cast<double>(area.inside) > min_fraction * static_cast<double>(area.total)) selection.push_back(label);
  if (selection.empty())
    throw Error(OptionName("mask") + ": no centre-view superpixel has more than " +
                std::to_string(min_fraction * 100.0) + " % of its area inside the mask");
  return SortedUnique(selection);
}

}  // namespace lfsp::edit
