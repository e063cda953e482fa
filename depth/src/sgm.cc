#include "lfsp/depth/sgm.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "lfsp/core/error.h"

namespace lfsp::depth {
namespace {

// One step along a path: out[d] = cost[d] + min(prev[d], prev[d±1] + p1, min(prev) + p2) - min(prev).
// Returns min(out) for the next step. The first and last labels (one neighbour each) are taken apart so the labels
// between run as one vectorised loop. The minimum starts from FLT_MAX and takes a value only when it is smaller, as
// the loop it replaced did, so a NaN cost never becomes it; over the other values it is exact in any order.
__attribute__((target_clones("avx2", "default"))) float PathStep(const float* __restrict cost,
                                                                 const float* __restrict previous, float previous_min,
                                                                 float p1, float p2, int labels, float* __restrict out,
                                                                 float* __restrict sum) {
  const float jump = previous_min + p2;
  const auto step = [&](int d, float below, float above) {
    const float best = std::min(std::min(previous[d], std::min(below, above) + p1), jump);
    out[d] = cost[d] + best - previous_min;
    sum[d] += out[d];
    return out[d];
  };
  constexpr float kNone = std::numeric_limits<float>::max();
  float out_min = std::min(std::min(kNone, step(0, kNone, previous[1])), step(labels - 1, previous[labels - 2], kNone));
#pragma omp simd reduction(min : out_min)
  for (int d = 1; d < labels - 1; ++d) out_min = std::min(out_min, step(d, previous[d - 1], previous[d + 1]));
  return out_min;
}

float StartPath(const float* cost, int labels, float* out, float* sum) {
  float out_min = std::numeric_limits<float>::max();
  for (int d = 0; d < labels; ++d) {
    out[d] = cost[d];
    sum[d] += cost[d];
    out_min = std::min(out_min, cost[d]);
  }
  return out_min;
}

class PenaltyModel {
 public:
  PenaltyModel(const cv::Mat& guide, const SgmOptions& options) : guide_(guide), options_(options) {}
  // p2 for the step from (x0, y0) to (x1, y1).
  float P2(int y0, int x0, int y1, int x1) const {
    const float* a = guide_.ptr<float>(y0) + 3 * x0;
    const float* b = guide_.ptr<float>(y1) + 3 * x1;
    const float difference = (std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2])) / 3.0f;
    return std::max(options_.p1, options_.p2 / (1.0f + difference / options_.edge_sigma));
  }
  float P1() const { return options_.p1; }

 private:
  const cv::Mat& guide_;
  const SgmOptions& options_;
};

// One scanline direction r = (dx, dy). Every path starts at a pixel whose predecessor p - r lies outside the
// image and runs to the opposite border; paths never share pixels, so they run in parallel without
// synchronisation (no per-row barriers, which stall badly when the cores are shared).
void AggregateDirection(const CostVolume& cost, const PenaltyModel& penalties, int dx, int dy, CostVolume& sum) {
  const int width = cost.width();
  const int height = cost.height();
  const int labels = cost.labels();
  auto inside = [&](int x, int y) { return x >= 0 && x < width && y >= 0 && y < height; };
  std::vector<std::pair<int, int>> starts;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (!inside(x - dx, y - dy)) starts.emplace_back(x, y);
    }
  }
  const int paths = static_cast<int>(starts.size());
#pragma omp parallel
  {
    std::vector<float> previous(static_cast<std::size_t>(labels));
    std::vector<float> current(static_cast<std::size_t>(labels));
#pragma omp for schedule(dynamic, 16)
    for (int i = 0; i < paths; ++i) {
      int x = starts[static_cast<std::size_t>(i)].first;
      int y = starts[static_cast<std::size_t>(i)].second;
      float previous_min = StartPath(cost.Curve(y, x), labels, previous.data(), sum.Curve(y, x));
      for (x += dx, y += dy; inside(x, y); x += dx, y += dy) {
        const float p2 = penalties.P2(y - dy, x - dx, y, x);
        previous_min = PathStep(cost.Curve(y, x), previous.data(), previous_min, penalties.P1(), p2, labels,
                                current.data(), sum.Curve(y, x));
        std::swap(previous, current);
      }
    }
  }
}

}  // namespace

SgmOptions PenaltiesForCost(const SgmOptions& options, const CostOptions& cost) {
  const float scale = CostRange(cost) / CostRange(CostOptions());
  SgmOptions scaled = options;
  scaled.p1 *= scale;
  scaled.p2 *= scale;
  return scaled;
}

CostVolume AggregateSemiGlobal(const CostVolume& cost, const cv::Mat& guide, const SgmOptions& options) {
  if (guide.type() != CV_32FC3 || guide.rows != cost.height() || guide.cols != cost.width()) {
    throw Error("semi-global aggregation: the guide must be a float RGB image of the cost volume's size");
  }
  if (!(options.p1 >= 0.0f) || !(options.p2 >= options.p1) || !(options.edge_sigma > 0.0f)) {
    throw Error("semi-global aggregation: need 0 <= p1 <= p2 and edge_sigma > 0");
  }
  if (cost.labels() < 2) throw Error("semi-global aggregation: needs at least 2 disparity labels");
  const PenaltyModel penalties(guide, options);
  CostVolume sum(cost.width(), cost.height(), cost.labels(), 0.0f);
  constexpr int kDirections[SemiGlobalPaths()][2] = {{1, 0}, {-1, 0},  {0, 1},  {0, -1},
                                                     {1, 1}, {-1, -1}, {1, -1}, {-1, 1}};
  for (const auto& direction : kDirections) AggregateDirection(cost, penalties, direction[0], direction[1], sum);
  return sum;
}

}  // namespace lfsp::depth
