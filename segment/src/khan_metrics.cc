#include "lfsp/segment/khan_metrics.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <opencv2/imgproc.hpp>
#include <unordered_map>

#include "lfsp/core/error.h"
#include "lfsp/core/rounding.h"
#include "lfsp/segment/metrics.h"

namespace lfsp::segment {
namespace {

void RequireViewDisparity(const Labels& labels, const std::vector<DisparityMap>& view_disparity, const char* what) {
  if (view_disparity.size() != labels.shape().Views())
    throw Error(std::string(what) + ": need one disparity map per view");
}

// Where the Sobel gradient of the label map is non-zero (replicated border), as Khan et al.'s boundary images: 1 on
// the boundary, 0 elsewhere. Computed in 64-bit integers, which is exact (label differences times the kernel's
// weights stay far below 2^62), as cv::Sobel in doubles also is for labels below 2^50: the same pixels, without
// converting each view to doubles and filtering it twice (0.14 -> 0.07 s for KhanBoundaryRecall on the Illum
// capture's 9x9 views).
std::vector<std::uint8_t> SobelBoundary(const std::int32_t* labels, int w, int h) {
  std::vector<std::uint8_t> boundary(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
  for (int y = 0; y < h; ++y) {
    const std::int32_t* above = labels + std::max(y - 1, 0) * w;
    const std::int32_t* row = labels + y * w;
    const std::int32_t* below = labels + std::min(y + 1, h - 1) * w;
    for (int x = 0; x < w; ++x) {
      const int left = std::max(x - 1, 0), right = std::min(x + 1, w - 1);
      const auto column = [&](int at) {
        return std::int64_t{above[at]} + 2 * std::int64_t{row[at]} + std::int64_t{below[at]};
      };
      const auto line = [&](const std::int32_t* r) {
        return std::int64_t{r[left]} + 2 * std::int64_t{r[x]} + std::int64_t{r[right]};
      };
      const std::int64_t gx = column(right) - column(left);
      const std::int64_t gy = line(below) - line(above);
      boundary[static_cast<std::size_t>(y) * w + x] = gx != 0 || gy != 0;
    }
  }
  return boundary;
}

// Pixels marked in `mask` with a pixel of `other` within `reach` (chessboard distance) inside the image: a count of
// mask & dilate(other), the dilation by a (2 reach + 1)-square as cv::dilate takes it (nothing beyond the border).
int CountNear(const std::vector<std::uint8_t>& mask, const std::vector<std::uint8_t>& other, int w, int h, int reach) {
  // Along the rows first: wide[i] says whether `other` is set within `reach` columns of i.
  std::vector<std::uint8_t> wide(other.size(), 0);
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* in = other.data() + static_cast<std::size_t>(y) * w;
    std::uint8_t* out = wide.data() + static_cast<std::size_t>(y) * w;
    int last = -(reach + 1);  // the last set column seen, scanning right; then the next, scanning left
    for (int x = 0; x < w; ++x) {
      if (in[x]) last = x;
      out[x] = x - last <= reach;
    }
    last = w + reach;
    for (int x = w - 1; x >= 0; --x) {
      if (in[x]) last = x;
      out[x] = out[x] || last - x <= reach;
    }
  }
  int count = 0;
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* m = mask.data() + static_cast<std::size_t>(y) * w;
    for (int x = 0; x < w; ++x) {
      if (!m[x]) continue;
      bool near = false;
      for (int yy = std::max(0, y - reach); yy <= std::min(h - 1, y + reach) && !near; ++yy)
        near = wide[static_cast<std::size_t>(yy) * w + x] != 0;
      count += near;
    }
  }
  return count;
}

}  // namespace

double KhanSelfSimilarityOfSums(const std::vector<double>& sums, std::size_t k_count, const LightFieldShape& shape) {
  if (k_count == 0) return 0.0;
  const ViewIndex c = shape.Centre();
  const int views = static_cast<int>(shape.Views());
  const double* centre = sums.data() + static_cast<std::size_t>(CameraNumber(c, shape.nu)) * k_count * 3;
  double total = 0.0;
  long long pairs = 0;
  for (int cam = 0; cam < views; ++cam) {
    const double* s = sums.data() + static_cast<std::size_t>(cam) * k_count * 3;
    for (std::size_t k = 0; k < k_count; ++k) {
      const double* here = s + k * 3;
      const double* there = centre + k * 3;
      if (here[2] == 0.0 || there[2] == 0.0) continue;  // absent from this view or from the centre: left out
      total += std::hypot(here[0] / here[2] - there[0] / there[2], here[1] / here[2] - there[1] / there[2]);
      ++pairs;
    }
  }
  return pairs > 0 ? total / static_cast<double>(pairs) : 0.0;
}

double KhanSelfSimilarity(const Labels& labels, const std::vector<DisparityMap>& view_disparity) {
  RequireViewDisparity(labels, view_disparity, "self-similarity (Khan)");
  std::size_t k_count = 0;
  const std::vector<double> sums = CarriedCentroidSums(labels, view_disparity, false, k_count);
  return KhanSelfSimilarityOfSums(sums, k_count, labels.shape());
}

double KhanLabelsPerPixel(const Labels& labels, const std::vector<DisparityMap>& view_disparity) {
  RequireViewDisparity(labels, view_disparity, "labels per pixel (Khan)");
  const LightFieldShape& shape = labels.shape();
  const int w = shape.width, h = shape.height;
  const ViewIndex c = shape.Centre();
  const std::int32_t* centre = labels.ViewData(c);
  const int views = static_cast<int>(shape.Views());
  constexpr std::int32_t kNothing = std::numeric_limits<std::int32_t>::min();
  std::vector<long long> differing(shape.ViewPixels(), 0);
#pragma omp parallel
  {
    std::vector<long long> local(shape.ViewPixels(), 0);
    std::vector<std::int32_t> carried(shape.ViewPixels());
    std::vector<float> front(shape.ViewPixels());
#pragma omp for schedule(dynamic)
    for (int cam = 0; cam < views; ++cam) {
      const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
      const double du = view.u - c.u, dv = view.v - c.v;
      const std::int32_t* l = labels.ViewData(view);
      const DisparityMap& d = view_disparity[static_cast<std::size_t>(cam)];
      std::fill(carried.begin(), carried.end(), kNothing);
      std::fill(front.begin(), front.end(), -std::numeric_limits<float>::infinity());
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          const float disparity = d.at(y, x);
          if (!std::isfinite(disparity)) continue;
          const long cx = RoundHalfAway(x + du * disparity), cy = RoundHalfAway(y + dv * disparity);
          if (cx < 0 || cy < 0 || cx >= w || cy >= h) continue;
          const std::size_t at =
              static_cast<std::size_t>(cy) * static_cast<std::size_t>(w) + static_cast<std::size_t>(cx);
          if (disparity > front[at]) {  // the front ray (larger disparity is nearer) is the one seen there
            front[at] = disparity;
            carried[at] = l[y * w + x];
          }
        }
      }
      for (int y0 = 0; y0 < h; ++y0) {
        for (int x0 = 0; x0 < w; ++x0) {
          const std::size_t at =
              static_cast<std::size_t>(y0) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x0);
          const std::int32_t label = carried[at];
          // Most carried labels are the centre pixel's own: settled without the 3x3 scan.
          if (centre[at] == label) continue;
          bool near = false;
          for (int y = std::max(0, y0 - 1); y <= std::min(h - 1, y0 + 1) && !near; ++y)
            for (int x = std::max(0, x0 - 1); x <= std::min(w - 1, x0 + 1); ++x)
              near = near || centre[y * w + x] == label;
          if (!near) ++local[at];
        }
      }
    }
#pragma omp critical
    for (std::size_t i = 0; i < differing.size(); ++i) differing[i] += local[i];
  }
  double sum = 0.0;
  for (long long count : differing) sum += static_cast<double>(count);
  return 1.0 + sum / static_cast<double>(differing.size());
}

double KhanBoundaryRecall(const Labels& labels, const Labels& gt) {
  if (labels.shape().width != gt.shape().width || labels.shape().height != gt.shape().height ||
      labels.shape().Views() != gt.shape().Views())
    throw Error("boundary recall (Khan): the labels and the ground truth differ in shape");
  const LightFieldShape& shape = labels.shape();
  const int views = static_cast<int>(shape.Views());
  constexpr int kReach = 2;  // Khan's tolerance: a 5 x 5 square
  std::vector<double> recall(static_cast<std::size_t>(views), -1.0);
  const int w = shape.width, h = shape.height;
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    const std::vector<std::uint8_t> truth = SobelBoundary(gt.ViewData(view), w, h);
    const long long total = std::count(truth.begin(), truth.end(), std::uint8_t{1});
    if (total == 0) continue;  // no boundary to recall (Khan's code would return NaN for the whole light field)
    const int hit = CountNear(truth, SobelBoundary(labels.ViewData(view), w, h), w, h, kReach);
    recall[static_cast<std::size_t>(cam)] = static_cast<double>(hit) / static_cast<double>(total);
  }
  double sum = 0.0;
  int counted = 0;
  for (double r : recall)
    if (r >= 0.0) {
      sum += r;
      ++counted;
    }
  return counted > 0 ? sum / counted : -1.0;
}

namespace {

// A superpixel's object for Khan's accuracy: the one it overlaps most in a view, and by how many rays.
struct ObjectChoice {
  int object = 0;
  long long overlap = 0;
};

// Tables of superpixel x object counts above this many entries are left to the ordered maps.
constexpr std::int64_t kDenseOverlapTable = std::int64_t{1} << 22;

// Each superpixel of one view with its most frequent object among the rays whose object is known (gt >= 0), the
// smallest object on ties, as Khan's code picks it.
std::vector<std::pair<int, ObjectChoice>> MostFrequentObjects(const std::int32_t* l, const std::int32_t* g,
                                                              std::size_t pixels) {
  std::int32_t min_s = std::numeric_limits<std::int32_t>::max(), max_s = std::numeric_limits<std::int32_t>::min();
  std::int32_t min_g = min_s, max_g = max_s;
  for (std::size_t i = 0; i < pixels; ++i) {
    if (g[i] < 0) continue;
    min_s = std::min(min_s, l[i]);
    max_s = std::max(max_s, l[i]);
    min_g = std::min(min_g, g[i]);
    max_g = std::max(max_g, g[i]);
  }
  std::vector<std::pair<int, ObjectChoice>> chosen;
  if (min_s > max_s) return chosen;
  const std::int64_t superpixels = std::int64_t{max_s} - min_s + 1, objects = std::int64_t{max_g} - min_g + 1;
  if (superpixels <= kDenseOverlapTable / objects) {
    // Counted in a table, then read object by object in increasing order: a later object wins only with more rays.
    std::vector<long long> count(static_cast<std::size_t>(superpixels * objects), 0);
    for (std::size_t i = 0; i < pixels; ++i)
      if (g[i] >= 0) ++count[static_cast<std::size_t>((std::int64_t{l[i]} - min_s) * objects + (g[i] - min_g))];
    for (std::int64_t s = 0; s < superpixels; ++s) {
      ObjectChoice here;
      for (std::int64_t o = 0; o < objects; ++o) {
        const long long n = count[static_cast<std::size_t>(s * objects + o)];
        if (n > here.overlap) here = {static_cast<int>(o + min_g), n};
      }
      if (here.overlap > 0) chosen.emplace_back(static_cast<int>(s + min_s), here);
    }
    return chosen;
  }
  std::unordered_map<int, std::map<int, long long>> overlaps;  // superpixel -> object -> rays (objects ordered)
  for (std::size_t i = 0; i < pixels; ++i)
    if (g[i] >= 0) ++overlaps[l[i]][g[i]];
  for (const auto& [superpixel, counts] : overlaps) {
    ObjectChoice here;
    for (const auto& [object, n] : counts)
      if (n > here.overlap) here = {object, n};
    chosen.emplace_back(superpixel, here);
  }
  return chosen;
}

}  // namespace

double KhanAchievableAccuracy(const Labels& labels, const Labels& gt) {
  if (labels.shape().width != gt.shape().width || labels.shape().height != gt.shape().height ||
      labels.shape().Views() != gt.shape().Views())
    throw Error("achievable accuracy (Khan): the labels and the ground truth differ in shape");
  const LightFieldShape& shape = labels.shape();
  // Khan's loop order: u outer, v inner; a later view wins only with a strictly larger overlap.
  std::vector<ViewIndex> order;
  for (int u = 0; u < shape.nu; ++u)
    for (int v = 0; v < shape.nv; ++v) order.push_back({u, v});
  const int views = static_cast<int>(order.size());
  // Each view's choices are counted in parallel (a 9x9 Illum segmentation took 0.3 s in ordered maps on one thread),
  // then merged in Khan's order; each superpixel appears once per view, so the merge does not depend on the order
  // within a view.
  std::vector<std::vector<std::pair<int, ObjectChoice>>> per_view(static_cast<std::size_t>(views));
#pragma omp parallel for schedule(dynamic)
  for (int k = 0; k < views; ++k) {
    const ViewIndex view = order[static_cast<std::size_t>(k)];
    per_view[static_cast<std::size_t>(k)] =
        MostFrequentObjects(labels.ViewData(view), gt.ViewData(view), shape.ViewPixels());
  }
  std::unordered_map<int, ObjectChoice> object_of;
  for (const auto& choices : per_view)
    for (const auto& [superpixel, here] : choices) {
      ObjectChoice& best = object_of[superpixel];
      if (here.overlap > best.overlap) best = here;
    }
  // Looked up once per ray (21.8 M for a 9x9 Illum segmentation): in a table over the superpixels' range when they
  // are dense (LFSP's 0..n-1) rather than by hashing, in the map otherwise.
  std::int64_t lowest = std::numeric_limits<std::int32_t>::max(), highest = std::numeric_limits<std::int32_t>::min();
  for (const auto& [superpixel, chosen] : object_of) {
    lowest = std::min<std::int64_t>(lowest, superpixel);
    highest = std::max<std::int64_t>(highest, superpixel);
  }
  const bool dense = !object_of.empty() && highest - lowest < kDenseOverlapTable;
  constexpr int kNoObject = std::numeric_limits<int>::min();  // object labels are >= 0 where they count
  std::vector<int> table(dense ? static_cast<std::size_t>(highest - lowest + 1) : 0, kNoObject);
  for (const auto& [superpixel, chosen] : object_of)
    if (dense) table[static_cast<std::size_t>(superpixel - lowest)] = chosen.object;
  const auto object = [&](std::int32_t superpixel) {
    if (dense)
      return superpixel < lowest || superpixel > highest ? kNoObject
                                                         : table[static_cast<std::size_t>(superpixel - lowest)];
    const auto found = object_of.find(superpixel);
    return found == object_of.end() ? kNoObject : found->second.object;
  };
  // The share of each view's known rays whose superpixel's object is theirs, views in parallel, summed in order.
  std::vector<double> share(static_cast<std::size_t>(views), -1.0);
#pragma omp parallel for schedule(dynamic)
  for (int k = 0; k < views; ++k) {
    const ViewIndex view = order[static_cast<std::size_t>(k)];
    const std::int32_t* l = labels.ViewData(view);
    const std::int32_t* g = gt.ViewData(view);
    long long right = 0, rays = 0;
    for (std::size_t i = 0; i < shape.ViewPixels(); ++i) {
      if (g[i] < 0) continue;
      ++rays;
      right += object(l[i]) == g[i];
    }
    if (rays > 0) share[static_cast<std::size_t>(k)] = static_cast<double>(right) / static_cast<double>(rays);
  }
  double sum = 0.0;
  int counted = 0;
  for (const double value : share) {
    if (value < 0.0) continue;
    sum += value;
    ++counted;
  }
  return counted > 0 ? sum / counted : -1.0;
}

double KhanAverageSize(const Labels& labels) {
  const cv::Mat centre = labels.View(labels.shape().Centre());
  std::unordered_map<int, long long> area;
  for (auto it = centre.begin<int>(); it != centre.end<int>(); ++it) ++area[*it];
  if (area.empty()) return 0.0;
  double sum = 0.0;
  for (const auto& [label, count] : area) sum += std::sqrt(static_cast<double>(count));
  return sum / static_cast<double>(area.size());
}

nlohmann::json ScoreKhan(const Labels& labels, const Labels* gt_labels,
                         const std::vector<DisparityMap>* gt_view_disparity,
                         std::optional<double> region_undersegmentation_error, std::optional<double> self_similarity) {
  nlohmann::json m;
  m["size"] = KhanAverageSize(labels);
  if (gt_view_disparity != nullptr) {
    m["self_similarity"] = self_similarity ? *self_similarity : KhanSelfSimilarity(labels, *gt_view_disparity);
    m["labels_per_pixel"] = KhanLabelsPerPixel(labels, *gt_view_disparity);
  }
  if (gt_labels != nullptr) {
    m["boundary_recall"] = KhanBoundaryRecall(labels, *gt_labels);
    m["undersegmentation_error"] = region_undersegmentation_error ? *region_undersegmentation_error
                                                                  : RegionUndersegmentationError(labels, *gt_labels);
    m["achievable_accuracy"] = KhanAchievableAccuracy(labels, *gt_labels);
  }
  return m;
}

}  // namespace lfsp::segment
