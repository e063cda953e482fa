#include "lfsp/edit/recolor.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "lfsp/core/error.h"

namespace lfsp::edit {
namespace {

// Membership test for label ids: a table indexed by label up to the largest selected id, or, for huge ids (labels
// need not be dense), a binary search in the sorted ids.
class SelectionTable {
 public:
  explicit SelectionTable(const std::vector<std::int32_t>& selection) : sorted_(selection) {
    std::sort(sorted_.begin(), sorted_.end());
    if (!sorted_.empty() && sorted_.front() < 0)
      throw Error("recolour: selected label ids must be >= 0, got " + std::to_string(sorted_.front()));
    if (!sorted_.empty() && sorted_.back() < kMaxTableSize) {
      selected_.assign(static_cast<std::size_t>(sorted_.back()) + 1, 0);
      for (const std::int32_t id : sorted_) selected_[static_cast<std::size_t>(id)] = 1;
    }
  }
  bool Contains(std::int32_t label) const {
    if (label < 0) return false;
    if (!selected_.empty() || sorted_.empty())
      return static_cast<std::size_t>(label) < selected_.size() && selected_[static_cast<std::size_t>(label)] != 0;
    return std::binary_search(sorted_.begin(), sorted_.end(), label);
  }

 private:
  static constexpr std::int32_t kMaxTableSize = 1 << 24;
  std::vector<std::int32_t> sorted_;
  std::vector<unsigned char> selected_;
};

cv::Mat EditStrengthWithTable(const cv::Mat& view_labels, const SelectionTable& table, float feather_px,
                              const cv::Mat& weights) {
  cv::Mat strength(view_labels.size(), CV_32FC1, cv::Scalar(0.0));
  // Unselected rays are non-zero in `outside`, as cv::distanceTransform measures the distance to the nearest zero.
  cv::Mat outside(view_labels.size(), CV_8UC1);
  bool any_selected = false;
  for (int y = 0; y < view_labels.rows; ++y) {
    const std::int32_t* labels = view_labels.ptr<std::int32_t>(y);
    float* s = strength.ptr<float>(y);
    unsigned char* o = outside.ptr<unsigned char>(y);
    for (int x = 0; x < view_labels.cols; ++x) {
      const bool selected = table.Contains(labels[x]);
      s[x] = selected ? 1.0f : 0.0f;
      o[x] = selected ? 0 : 1;
      any_selected = any_selected || selected;
    }
  }
  if (feather_px <= 0.0f || !any_selected) return strength;

  cv::Mat distance;
  cv::distanceTransform(outside, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  for (int y = 0; y < view_labels.rows; ++y) {
    const float* r = distance.ptr<float>(y);
    const unsigned char* o = outside.ptr<unsigned char>(y);
    const float* w = weights.empty() ? nullptr : weights.ptr<float>(y);
    float* s = strength.ptr<float>(y);
    for (int x = 0; x < view_labels.cols; ++x) {
      if (o[x] == 0 || r[x] > feather_px) continue;
      float ramp = 1.0f - r[x] / (feather_px + 1.0f);
      if (w != nullptr) ramp *= std::min(1.0f, std::max(0.0f, w[x]));
      s[x] = ramp;
    }
  }
  return strength;
}

struct ViewCounts {
  std::size_t selected = 0;
  std::size_t feather = 0;
  std::size_t changed = 0;
};

// Edits the rays of one view (RGB samples, row-major) with strength > 0, blending by strength.
ViewCounts RecolorView(float* samples, const cv::Mat& strength, const ColourAdjustment& adjustment, Transfer transfer) {
  ViewCounts counts;
  const float* s = strength.ptr<float>(0);
  const std::size_t pixels = strength.total();
  // Gather the rays to edit into one contiguous list, so the colour conversion touches nothing else.
  std::vector<std::size_t> where;
  for (std::size_t i = 0; i < pixels; ++i) {
    if (s[i] <= 0.0f) continue;
    where.push_back(i);
    if (s[i] >= 1.0f) {
      ++counts.selected;
    } else {
      ++counts.feather;
    }
  }
  if (where.empty()) return counts;
  cv::Mat edited(static_cast<int>(where.size()), 1, CV_32FC3);
  float* e = edited.ptr<float>(0);
  for (std::size_t k = 0; k < where.size(); ++k) std::copy_n(samples + 3 * where[k], 3, e + 3 * k);
  AdjustColours(edited, adjustment, transfer);

  // A ray with strength 1 takes the edited colour exactly; the feather band blends.
  for (std::size_t k = 0; k < where.size(); ++k) {
    float* ray = samples + 3 * where[k];
    const float alpha = s[where[k]];
    bool changed = false;
    for (std::size_t c = 0; c < 3; ++c) {
      const float target = e[3 * k + c];
      const float value = alpha >= 1.0f ? target : ray[c] + alpha * (target - ray[c]);
      changed = changed || value != ray[c];
      ray[c] = value;
    }
    if (changed) ++counts.changed;
  }
  return counts;
}

void CheckOptions(const RecolorOptions& options) {
  ValidateAdjustment(options.adjustment);
  if (!(options.feather_px >= 0.0f) || !std::isfinite(options.feather_px))
    throw Error(OptionName("feather") + ": expected a finite width >= 0 pixels, got " +
                std::to_string(options.feather_px));
}

}  // namespace

cv::Mat EditStrength(const cv::Mat& view_labels, const std::vector<std::int32_t>& selection, float feather_px,
                     const cv::Mat& weights) {
  if (view_labels.type() != CV_32SC1) throw Error("edit strength: expected an int32 label image");
  if (!weights.empty() && (weights.type() != CV_32FC1 || weights.size() != view_labels.size()))
    throw Error("edit strength: weights must be CV_32FC1 of the label image's size");
  return EditStrengthWithTable(view_labels, SelectionTable(selection), feather_px, weights);
}

RecolorStats Recolor(LightField& light_field, const Labels& labels, const std::vector<std::int32_t>& selection,
                     const RecolorOptions& options) {
  CheckOptions(options);
  const LightFieldShape& shape = light_field.shape();
  if (light_field.empty() || shape.channels != 3)
    throw Error("recolour: expected an RGB light field (3 channels), got " + ToString(shape));
  RequireLabelsMatch(labels, shape, "recolour");
  if (selection.empty()) throw Error("recolour: the selection is empty");
  const SelectionTable table(selection);

  // Views are independent: one per thread.
  std::vector<ViewCounts> counts(shape.Views());
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    const cv::Mat weights =
        options.use_ray_weights && light_field.HasWeights() ? light_field.WeightView(view) : cv::Mat();
    const cv::Mat strength = EditStrengthWithTable(labels.View(view), table, options.feather_px, weights);
    counts[static_cast<std::size_t>(cam)] =
        RecolorView(light_field.ViewData(view), strength, options.adjustment, light_field.transfer);
  }

  RecolorStats stats;
  for (const ViewCounts& view_counts : counts) {
    stats.selected_rays += view_counts.selected;
    stats.feather_rays += view_counts.feather;
    stats.changed_rays += view_counts.changed;
    stats.selected_rays_per_view.push_back(view_counts.selected);
  }
  return stats;
}

}  // namespace lfsp::edit
