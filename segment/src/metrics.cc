#include "lfsp/segment/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <unordered_map>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/rounding.h"
#include "warp.h"

namespace lfsp::segment {
namespace {

void CheckSameSize(const cv::Mat& labels, const cv::Mat& gt) {
  if (labels.size() != gt.size() || labels.type() != CV_32SC1 || gt.type() != CV_32SC1) {
    throw Error("segmentation metrics: label maps must be CV_32SC1 of the same size");
  }
}

void CheckSameShape(const Labels& labels, const Labels& gt) {
  const LightFieldShape& a = labels.shape();
  const LightFieldShape& b = gt.shape();
  if (a.nu != b.nu || a.nv != b.nv || a.width != b.width || a.height != b.height) {
    throw Error("segmentation metrics: labels are " + ToString(a) + " but the ground truth is " + ToString(b));
  }
}

// Pixels where a 4-neighbour has another label (both sides of a label change are boundary).
cv::Mat BoundaryMask(const cv::Mat& labels) {
  cv::Mat mask = cv::Mat::zeros(labels.size(), CV_8U);
  for (int y = 0; y < labels.rows; ++y) {
    const int* row = labels.ptr<int>(y);
    const int* below = y + 1 < labels.rows ? labels.ptr<int>(y + 1) : nullptr;
    for (int x = 0; x < labels.cols; ++x) {
      if (x + 1 < labels.cols && row[x + 1] != row[x]) mask.at<uchar>(y, x) = mask.at<uchar>(y, x + 1) = 1;
      if (below != nullptr && below[x] != row[x]) mask.at<uchar>(y, x) = mask.at<uchar>(y + 1, x) = 1;
    }
  }
  return mask;
}

// Overlap counts |S_j n G_i| with the sizes |S_j| (over ground-truth-labelled pixels) and |G_i|.
struct Overlaps {
  std::unordered_map<std::uint64_t, long long> joint;  // (j << 32 | i) -> count
  std::unordered_map<int, long long> superpixel;
  std::unordered_map<int, long long> region;
  long long pixels = 0;
};

// Label ids in practice are small and non-negative (superpixels 0 .. K-1, a few objects): up to this many
// (superpixel, region) pairs are counted in a dense table, which is an order of magnitude faster than hashing every
// pixel (the evaluation of a full Illum capture spent a second there); other ids are hashed.
constexpr std::int64_t kDensePairs = std::int64_t{1} << 20;

// The ranges of the ids of `labels` and of `gt` over the pixels where gt >= 0 (min > max when there are none).
void IdRanges(const cv::Mat& labels, const cv::Mat& gt, int& min_s, int& max_s, int& min_g, int& max_g) {
  min_s = min_g = std::numeric_limits<int>::max();
  max_s = max_g = std::numeric_limits<int>::min();
  for (int y = 0; y < labels.rows; ++y) {
    const int* s = labels.ptr<int>(y);
    const int* g = gt.ptr<int>(y);
    for (int x = 0; x < labels.cols; ++x) {
      if (g[x] < 0) continue;
      min_s = std::min(min_s, s[x]);
      max_s = std::max(max_s, s[x]);
      min_g = std::min(min_g, g[x]);
      max_g = std::max(max_g, g[x]);
    }
  }
}

std::uint64_t PairKey(int superpixel, int region) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(superpixel)) << 32) |
         static_cast<std::uint32_t>(region);
}

Overlaps CountOverlapsHashed(const cv::Mat& labels, const cv::Mat& gt) {
  Overlaps o;
  for (int y = 0; y < labels.rows; ++y) {
    const int* s = labels.ptr<int>(y);
    const int* g = gt.ptr<int>(y);
    for (int x = 0; x < labels.cols; ++x) {
      if (g[x] < 0) continue;
      ++o.joint[PairKey(s[x], g[x])];
      ++o.superpixel[s[x]];
      ++o.region[g[x]];
      ++o.pixels;
    }
  }
  return o;
}

Overlaps CountOverlaps(const cv::Mat& labels, const cv::Mat& gt) {
  CheckSameSize(labels, gt);
  int min_s = 0, max_s = 0, min_g = 0, max_g = 0;
  IdRanges(labels, gt, min_s, max_s, min_g, max_g);
  if (min_s > max_s) return {};
  const std::int64_t superpixels = std::int64_t{max_s} - min_s + 1, regions = std::int64_t{max_g} - min_g + 1;
  if (superpixels > kDensePairs / regions) return CountOverlapsHashed(labels, gt);
  std::vector<long long> joint(static_cast<std::size_t>(superpixels * regions), 0);
  for (int y = 0; y < labels.rows; ++y) {
    const int* s = labels.ptr<int>(y);
    const int* g = gt.ptr<int>(y);
    for (int x = 0; x < labels.cols; ++x) {
      if (g[x] >= 0) ++joint[static_cast<std::size_t>((std::int64_t{s[x]} - min_s) * regions + (g[x] - min_g))];
    }
  }
  Overlaps o;
  for (std::int64_t j = 0; j < superpixels; ++j) {
    for (std::int64_t i = 0; i < regions; ++i) {
      const long long count = joint[static_cast<std::size_t>(j * regions + i)];
      if (count == 0) continue;
      const int superpixel = static_cast<int>(j + min_s), region = static_cast<int>(i + min_g);
      o.joint[PairKey(superpixel, region)] = count;
      o.superpixel[superpixel] += count;
      o.region[region] += count;
      o.pixels += count;
    }
  }
  return o;
}

int SuperpixelOf(std::uint64_t key) { return static_cast<int>(static_cast<std::uint32_t>(key >> 32)); }
int RegionOf(std::uint64_t key) { return static_cast<int>(static_cast<std::uint32_t>(key & 0xffffffffu)); }

// Mean of per-view scores in view order; views where the score is negative (undefined) are skipped.
double MeanOfDefined(const std::vector<double>& values) {
  double sum = 0.0;
  int count = 0;
  for (double value : values) {
    if (value < 0.0) continue;
    sum += value;
    ++count;
  }
  return count > 0 ? sum / count : -1.0;
}

// Mean over views of a per-view score, the views scored in parallel.
template <typename Score>
double MeanOverViews(const LightFieldShape& shape, Score score) {
  const int views = static_cast<int>(shape.Views());
  std::vector<double> values(static_cast<std::size_t>(views));
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam)
    values[static_cast<std::size_t>(cam)] = score(ViewFromCameraNumber(cam, shape.nu));
  return MeanOfDefined(values);
}

// The overlap scores of one view's counted overlaps (-1: undefined, no labelled pixel).
double UndersegmentationErrorOf(const Overlaps& o) {
  if (o.pixels == 0) return -1.0;
  long long error = 0;
  for (const auto& [key, inside] : o.joint) {
    const long long outside = o.superpixel.at(SuperpixelOf(key)) - inside;
    error += std::min(inside, outside);
  }
  return static_cast<double>(error) / static_cast<double>(o.pixels);
}

double RegionUndersegmentationErrorOf(const Overlaps& o) {
  if (o.region.empty()) return -1.0;
  std::unordered_map<int, double> error_of_region;
  for (const auto& [key, inside] : o.joint) {
    const long long size = o.superpixel.at(SuperpixelOf(key));
    const long long error = 2 * inside > size ? size - inside : inside;
    error_of_region[RegionOf(key)] += static_cast<double>(error);
  }
  double sum = 0.0;
  for (const auto& [region, size] : o.region) sum += error_of_region[region] / static_cast<double>(size);
  return sum / static_cast<double>(o.region.size());
}

double AchievableSegmentationAccuracyOf(const Overlaps& o) {
  if (o.pixels == 0) return -1.0;
  std::unordered_map<int, long long> best;
  for (const auto& [key, inside] : o.joint) {
    long long& b = best[SuperpixelOf(key)];
    b = std::max(b, inside);
  }
  long long sum = 0;
  for (const auto& [superpixel, count] : best) sum += count;
  return static_cast<double>(sum) / static_cast<double>(o.pixels);
}

}  // namespace

double BoundaryRecall2D(const cv::Mat& labels, const cv::Mat& gt, int tolerance) {
  CheckSameSize(labels, gt);
  const cv::Mat gt_boundary = BoundaryMask(gt);
  const int total = cv::countNonZero(gt_boundary);
  if (total == 0) return -1.0;
  cv::Mat near;
  cv::dilate(BoundaryMask(labels), near,
             cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * tolerance + 1, 2 * tolerance + 1)));
  cv::Mat hit;
  cv::bitwise_and(gt_boundary, near, hit);
  return static_cast<double>(cv::countNonZero(hit)) / total;
}

double UndersegmentationError2D(const cv::Mat& labels, const cv::Mat& gt) {
  return UndersegmentationErrorOf(CountOverlaps(labels, gt));
}

double RegionUndersegmentationError2D(const cv::Mat& labels, const cv::Mat& gt) {
  return RegionUndersegmentationErrorOf(CountOverlaps(labels, gt));
}

double AchievableSegmentationAccuracy2D(const cv::Mat& labels, const cv::Mat& gt) {
  return AchievableSegmentationAccuracyOf(CountOverlaps(labels, gt));
}

double Compactness2D(const cv::Mat& labels) {
  if (labels.type() != CV_32SC1 || labels.empty()) throw Error("compactness: labels must be a CV_32SC1 map");
  double min_id = 0.0, max_id = 0.0;
  cv::minMaxLoc(labels, &min_id, &max_id);
  const auto ids = static_cast<std::int64_t>(max_id - min_id) + 1;
  // Area and perimeter (4-neighbour edges to another label or the border) of each label; dense when the ids allow.
  std::vector<long long> dense_area, dense_perimeter;
  std::unordered_map<int, long long> hashed_area, hashed_perimeter;
  const bool dense = ids <= kDensePairs;
  if (dense) {
    dense_area.assign(static_cast<std::size_t>(ids), 0);
    dense_perimeter.assign(static_cast<std::size_t>(ids), 0);
  }
  const int base = static_cast<int>(min_id);
  for (int y = 0; y < labels.rows; ++y) {
    const int* row = labels.ptr<int>(y);
    const int* above = y > 0 ? labels.ptr<int>(y - 1) : nullptr;
    const int* below = y + 1 < labels.rows ? labels.ptr<int>(y + 1) : nullptr;
    for (int x = 0; x < labels.cols; ++x) {
      const int k = row[x];
      const int edges = (x == 0 || row[x - 1] != k) + (x + 1 == labels.cols || row[x + 1] != k) +
                        (above == nullptr || above[x] != k) + (below == nullptr || below[x] != k);
      if (dense) {
        ++dense_area[static_cast<std::size_t>(k - base)];
        dense_perimeter[static_cast<std::size_t>(k - base)] += edges;
      } else {
        ++hashed_area[k];
        hashed_perimeter[k] += edges;
      }
    }
  }
  const double n = static_cast<double>(labels.total());
  double sum = 0.0;
  const auto add = [&](long long a, long long l) {
    sum += (static_cast<double>(a) / n) * 4.0 * std::numbers::pi * static_cast<double>(a) /
           (static_cast<double>(l) * static_cast<double>(l));
  };
  if (dense) {
    for (std::size_t k = 0; k < dense_area.size(); ++k) {
      if (dense_area[k] > 0) add(dense_area[k], dense_perimeter[k]);
    }
  } else {
    for (const auto& [k, a] : hashed_area) add(a, hashed_perimeter[k]);
  }
  return sum;
}

double BoundaryRecall(const Labels& labels, const Labels& gt, int tolerance) {
  CheckSameShape(labels, gt);
  return MeanOverViews(labels.shape(),
                       [&](ViewIndex v) { return BoundaryRecall2D(labels.View(v), gt.View(v), tolerance); });
}

double UndersegmentationError(const Labels& labels, const Labels& gt) {
  CheckSameShape(labels, gt);
  return MeanOverViews(labels.shape(),
                       [&](ViewIndex v) { return UndersegmentationError2D(labels.View(v), gt.View(v)); });
}

double RegionUndersegmentationError(const Labels& labels, const Labels& gt) {
  CheckSameShape(labels, gt);
  return MeanOverViews(labels.shape(),
                       [&](ViewIndex v) { return RegionUndersegmentationError2D(labels.View(v), gt.View(v)); });
}

double AchievableSegmentationAccuracy(const Labels& labels, const Labels& gt) {
  CheckSameShape(labels, gt);
  return MeanOverViews(labels.shape(),
                       [&](ViewIndex v) { return AchievableSegmentationAccuracy2D(labels.View(v), gt.View(v)); });
}

OverlapScores ScoreOverlaps(const Labels& labels, const Labels& gt) {
  CheckSameShape(labels, gt);
  const LightFieldShape& shape = labels.shape();
  const std::size_t views = shape.Views();
  std::vector<double> ue(views), region_ue(views), asa(views);
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < static_cast<int>(views); ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    const Overlaps o = CountOverlaps(labels.View(view), gt.View(view));
    const auto at = static_cast<std::size_t>(cam);
    ue[at] = UndersegmentationErrorOf(o);
    region_ue[at] = RegionUndersegmentationErrorOf(o);
    asa[at] = AchievableSegmentationAccuracyOf(o);
  }
  return {MeanOfDefined(ue), MeanOfDefined(region_ue), MeanOfDefined(asa)};
}

double Compactness(const Labels& labels) {
  return MeanOverViews(labels.shape(), [&](ViewIndex v) { return Compactness2D(labels.View(v)); });
}

namespace {

// The number of distinct values among `count` labels. Labels are dense in practice (LFSP's 0..n-1, -1 for
// unlabelled rays), so they are ticked off in a table over their range: hashing each of a 9x9 Illum segmentation's
// 21.8 M rays took 0.2 s, three times in a pipeline. Labels spread far wider than their count are sorted instead.
int DistinctLabels(const std::int32_t* values, std::size_t count) {
  if (count == 0) return 0;
  const auto [lowest, highest] = std::minmax_element(values, values + count);
  const std::uint64_t range = static_cast<std::uint64_t>(static_cast<std::int64_t>(*highest) - *lowest) + 1;
  if (range <= 4 * static_cast<std::uint64_t>(count) + 1024) {
    std::vector<std::uint8_t> seen(static_cast<std::size_t>(range), 0);
    for (std::size_t i = 0; i < count; ++i)
      seen[static_cast<std::size_t>(static_cast<std::int64_t>(values[i]) - *lowest)] = 1;
    return static_cast<int>(std::count(seen.begin(), seen.end(), std::uint8_t{1}));
  }
  std::vector<std::int32_t> sorted(values, values + count);
  std::sort(sorted.begin(), sorted.end());
  return static_cast<int>(std::unique(sorted.begin(), sorted.end()) - sorted.begin());
}

}  // namespace

int CentreLabelCount(const Labels& labels) {
  return DistinctLabels(labels.ViewData(labels.shape().Centre()), labels.shape().ViewPixels());
}

int LabelCount(const Labels& labels) { return DistinctLabels(labels.data(), labels.size()); }

double EffectiveLabelRatio(int centre_label_count, int label_count) {
  return label_count > 0 ? static_cast<double>(centre_label_count) / label_count : 0.0;
}

double EffectiveLabelRatio(const Labels& labels) {
  return EffectiveLabelRatio(CentreLabelCount(labels), LabelCount(labels));
}

std::vector<DisparityMap> PropagateDisparity(const DisparityMap& centre, const LightFieldShape& shape) {
  if (centre.width() != shape.width || centre.height() != shape.height) {
    throw Error("disparity is " + std::to_string(centre.width()) + "x" + std::to_string(centre.height()) +
                " but the views are " + std::to_string(shape.width) + "x" + std::to_string(shape.height));
  }
  float max_abs = 0.0f;
  for (int i = 0; i < shape.width * shape.height; ++i) {
    if (std::isfinite(centre.data()[i])) max_abs = std::max(max_abs, std::abs(centre.data()[i]));
  }
  const ViewIndex c = shape.Centre();
  const int views = static_cast<int>(shape.Views());
  std::vector<DisparityMap> out(static_cast<std::size_t>(views));
  const std::vector<std::int32_t> ones(shape.ViewPixels(), 0);
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    DisparityMap map(shape.width, shape.height);
    if (view == c) {
      std::copy(centre.data(), centre.data() + shape.ViewPixels(), map.data());
    } else {
      const int du = view.u - c.u, dv = view.v - c.v;
      std::vector<std::int32_t> hit(shape.ViewPixels());
      ForwardWarp(ones.data(), centre.data(), shape.width, shape.height, du, dv, hit.data(), map.data());
      FillHoles(hit.data(), map.data(), shape.width, shape.height, du, dv, FillReach(max_abs, du, dv));
    }
    out[static_cast<std::size_t>(cam)] = std::move(map);
  }
  return out;
}

namespace {

// Adds every view's rays, carried to the centre view by their disparity, to `all` and those landing inside the
// centre view's frame to `in_frame` ([cam][label][3] each, either may be null): one read of the labels and
// disparities serves both variants, which the evaluation asks for together. Each array receives its rays in the same
// order whichever else is filled, so its sums are the same bytes.
void AddCarriedRays(const Labels& labels, const std::vector<DisparityMap>& view_disparity, std::size_t k_count,
                    double* all, double* in_frame) {
  const LightFieldShape& shape = labels.shape();
  const ViewIndex c = shape.Centre();
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    const double du = view.u - c.u, dv = view.v - c.v;
    const std::int32_t* l = labels.ViewData(view);
    const DisparityMap& d = view_disparity[static_cast<std::size_t>(cam)];
    const std::size_t view_offset = static_cast<std::size_t>(cam) * k_count * 3;
    double* s_all = all == nullptr ? nullptr : all + view_offset;
    double* s_in = in_frame == nullptr ? nullptr : in_frame + view_offset;
    for (int y = 0; y < shape.height; ++y) {
      for (int x = 0; x < shape.width; ++x) {
        const std::int32_t k = l[y * shape.width + x];
        const float disparity = d.at(y, x);
        if (k < 0 || !std::isfinite(disparity)) continue;
        const double px = x + du * disparity;  // Eq. 9 with the project's sign
        const double py = y + dv * disparity;
        const std::size_t at = static_cast<std::size_t>(k) * 3;
        if (s_all != nullptr) {
          s_all[at] += px;
          s_all[at + 1] += py;
          s_all[at + 2] += 1.0;
        }
        if (s_in == nullptr || px < -0.5 || py < -0.5 || px > shape.width - 0.5 || py > shape.height - 0.5) continue;
        s_in[at] += px;
        s_in[at + 1] += py;
        s_in[at + 2] += 1.0;
      }
    }
  }
}

// The largest label + 1 (0 if none), after checking there is a disparity map per view.
std::size_t CarriedLabelCount(const Labels& labels, const std::vector<DisparityMap>& view_disparity) {
  if (view_disparity.size() != labels.shape().Views()) throw Error("self-similarity: need one disparity map per view");
  int max_label = -1;
  for (std::size_t i = 0; i < labels.size(); ++i) max_label = std::max(max_label, labels.data()[i]);
  return static_cast<std::size_t>(max_label + 1);
}

}  // namespace

std::vector<double> CarriedCentroidSums(const Labels& labels, const std::vector<DisparityMap>& view_disparity,
                                        bool in_frame_only, std::size_t& label_count) {
  label_count = CarriedLabelCount(labels, view_disparity);
  std::vector<double> sums(labels.shape().Views() * label_count * 3, 0.0);
  AddCarriedRays(labels, view_disparity, label_count, in_frame_only ? nullptr : sums.data(),
                 in_frame_only ? sums.data() : nullptr);
  return sums;
}

CarriedCentroids CarriedCentroidSumsBoth(const Labels& labels, const std::vector<DisparityMap>& view_disparity) {
  CarriedCentroids centroids;
  centroids.label_count = CarriedLabelCount(labels, view_disparity);
  const std::size_t size = labels.shape().Views() * centroids.label_count * 3;
  centroids.all.assign(size, 0.0);
  centroids.in_frame.assign(size, 0.0);
  AddCarriedRays(labels, view_disparity, centroids.label_count, centroids.all.data(), centroids.in_frame.data());
  return centroids;
}

double SelfSimilarityOfSums(const std::vector<double>& sums, std::size_t k_count, const LightFieldShape& shape) {
  if (k_count == 0) return 0.0;
  const ViewIndex c = shape.Centre();
  const int views = static_cast<int>(shape.Views());
  const int centre_cam = CameraNumber(c, shape.nu);
  double total = 0.0;
  int counted = 0;
  for (std::size_t k = 0; k < k_count; ++k) {
    const double* ref = sums.data() + (static_cast<std::size_t>(centre_cam) * k_count + k) * 3;
    if (ref[2] <= 0) continue;
    const double cx = ref[0] / ref[2], cy = ref[1] / ref[2];
    double sum = 0.0;
    int present = 0;
    for (int cam = 0; cam < views; ++cam) {
      if (cam == centre_cam) continue;
      const double* e = sums.data() + (static_cast<std::size_t>(cam) * k_count + k) * 3;
      if (e[2] <= 0) continue;
      sum += std::hypot(e[0] / e[2] - cx, e[1] / e[2] - cy);
      ++present;
    }
    if (present == 0) continue;
    total += sum / present;
    ++counted;
  }
  return counted > 0 ? total / counted : 0.0;
}

double SelfSimilarity(const Labels& labels, const std::vector<DisparityMap>& view_disparity, bool in_frame_only) {
  std::size_t k_count = 0;
  const std::vector<double> sums = CarriedCentroidSums(labels, view_disparity, in_frame_only, k_count);
  return SelfSimilarityOfSums(sums, k_count, labels.shape());
}

Labels FollowToCentre(const Labels& labels, const std::vector<DisparityMap>& view_disparity) {
  const LightFieldShape& shape = labels.shape();
  if (view_disparity.size() != shape.Views()) throw Error("follow to centre: need one disparity map per view");
  const ViewIndex c = shape.Centre();
  const std::int32_t* centre = labels.ViewData(c);
  Labels out = labels;
  int max_label = -1;
  for (std::size_t i = 0; i < labels.size(); ++i) max_label = std::max(max_label, labels.data()[i]);
  const int views = static_cast<int>(shape.Views());
  const int w = shape.width, h = shape.height;
  std::vector<std::unordered_map<int, int>> renames(static_cast<std::size_t>(views));
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    if (view == c) continue;
    const std::int32_t* l = labels.ViewData(view);
    const DisparityMap& d = view_disparity[static_cast<std::size_t>(cam)];
    std::unordered_map<std::uint64_t, int> votes;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const float disparity = d.at(y, x);
        if (!std::isfinite(disparity)) continue;
        const int x0 = RoundHalfAway(x + (view.u - c.u) * disparity);
        const int y0 = RoundHalfAway(y + (view.v - c.v) * disparity);
        if (x0 < 0 || y0 < 0 || x0 >= w || y0 >= h) continue;
        ++votes[PairKey(l[y * w + x], centre[y0 * w + x0])];
      }
    }
    std::unordered_map<int, std::pair<int, int>> best;  // view label -> (centre label, votes)
    for (const auto& [key, count] : votes) {
      const int label = static_cast<int>(key >> 32), target = static_cast<int>(key & 0xffffffffu);
      auto [it, inserted] = best.try_emplace(label, target, count);
      if (!inserted && count > it->second.second) it->second = {target, count};
    }
    for (const auto& [label, target] : best) renames[static_cast<std::size_t>(cam)][label] = target.first;
  }
  int fresh = max_label + 1;
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    if (view == c) continue;
    std::unordered_map<int, int>& rename = renames[static_cast<std::size_t>(cam)];
    std::int32_t* o = out.ViewData(view);
    for (std::size_t i = 0; i < shape.ViewPixels(); ++i) {
      auto [it, inserted] = rename.try_emplace(o[i], fresh);
      if (inserted) ++fresh;
      o[i] = it->second;
    }
  }
  return out;
}

double LabelsPerPixel(const Labels& labels, const DisparityMap& centre_disparity,
                      const std::vector<DisparityMap>& view_disparity) {
  const LightFieldShape& shape = labels.shape();
  if (view_disparity.size() != shape.Views()) throw Error("labels per pixel: need one disparity map per view");
  const ViewIndex c = shape.Centre();
  const std::int32_t* centre = labels.ViewData(c);
  const int w = shape.width, h = shape.height;
  // Each side view's offset, labels and disparity, looked up once instead of per pixel.
  struct SideView {
    int du, dv;
    const std::int32_t* labels;
    const DisparityMap* disparity;
  };
  std::vector<SideView> sides;
  for (int cam = 0; cam < static_cast<int>(shape.Views()); ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    if (view == c) continue;
    sides.push_back(
        {view.u - c.u, view.v - c.v, labels.ViewData(view), &view_disparity[static_cast<std::size_t>(cam)]});
  }
  // A band of centre rows at a time, view by view: the rows a band reaches in one side view are read from memory once
  // and then from cache. Pixel by pixel, each pixel read its rays in all 80 views (0.18 s on the Illum capture's 9x9
  // views; 0.09 s now). Each pixel keeps the distinct labels of its 3x3 window (most windows hold one or two) and the
  // foreign ones found so far; how many there are does not depend on the order the views are visited in.
  constexpr int kBandRows = 8;
  constexpr int kWindow = 9;
  const int bands = (h + kBandRows - 1) / kBandRows;
  const int most_foreign = static_cast<int>(sides.size());
  double total = 0.0;
#pragma omp parallel reduction(+ : total)
  {
    const std::size_t band_pixels = static_cast<std::size_t>(kBandRows) * static_cast<std::size_t>(w);
    std::vector<std::int32_t> window(band_pixels * kWindow),
        foreign(band_pixels * static_cast<std::size_t>(most_foreign));
    std::vector<std::uint8_t> window_count(band_pixels);
    std::vector<std::uint16_t> foreign_count(band_pixels);  // up to the side views: 224 for 15 x 15
#pragma omp for schedule(dynamic)
    for (int band = 0; band < bands; ++band) {
      const int top = band * kBandRows, bottom = std::min(h, top + kBandRows);
      for (int y0 = top; y0 < bottom; ++y0) {
        for (int x0 = 0; x0 < w; ++x0) {
          const std::size_t p = static_cast<std::size_t>(y0 - top) * static_cast<std::size_t>(w) + x0;
          std::int32_t* distinct = &window[p * kWindow];
          int count = 0;
          for (int y = std::max(0, y0 - 1); y <= std::min(h - 1, y0 + 1); ++y)
            for (int x = std::max(0, x0 - 1); x <= std::min(w - 1, x0 + 1); ++x)
              if (std::find(distinct, distinct + count, centre[y * w + x]) == distinct + count)
                distinct[count++] = centre[y * w + x];
          window_count[p] = static_cast<std::uint8_t>(count);
          foreign_count[p] = 0;
        }
      }
      for (const SideView& side : sides) {
        for (int y0 = top; y0 < bottom; ++y0) {
          for (int x0 = 0; x0 < w; ++x0) {
            const float d = centre_disparity.at(y0, x0);
            if (!std::isfinite(d)) continue;
            const int x = RoundHalfAway(x0 - side.du * d);
            const int y = RoundHalfAway(y0 - side.dv * d);
            if (x < 0 || y < 0 || x >= w || y >= h) continue;
            if (std::abs(side.disparity->at(y, x) - d) > 0.5f) continue;  // occluded
            const std::int32_t k = side.labels[y * w + x];
            const std::size_t p = static_cast<std::size_t>(y0 - top) * static_cast<std::size_t>(w) + x0;
            const std::int32_t* distinct = &window[p * kWindow];
            if (std::find(distinct, distinct + window_count[p], k) != distinct + window_count[p]) continue;
            std::int32_t* found = &foreign[p * static_cast<std::size_t>(most_foreign)];
            if (std::find(found, found + foreign_count[p], k) == found + foreign_count[p])
              found[foreign_count[p]++] = k;
          }
        }
      }
      for (int y0 = top; y0 < bottom; ++y0)
        for (int x0 = 0; x0 < w; ++x0)
          if (std::isfinite(centre_disparity.at(y0, x0)))
            total += static_cast<double>(foreign_count[static_cast<std::size_t>(y0 - top) * w + x0]);
    }
  }
  return 1.0 + total / (static_cast<double>(w) * h);
}

}  // namespace lfsp::segment
