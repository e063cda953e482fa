#include "lfsp/depth/occlusion_alternatives.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "lfsp/core/error.h"

namespace lfsp::depth {
namespace {

// The unit normal of the edge whose views-along pair is `along` (OcclusionMap::along): a quarter turn from the
// pair's direction.
cv::Point2d EdgeNormal(int along) {
  const double angle = (along + kSectors / 4) * 2.0 * std::numbers::pi / kSectors;
  return {std::cos(angle), std::sin(angle)};
}

float ColourDifference(const cv::Vec3f& a, const cv::Vec3f& b) {
  return (std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2])) / 3.0f;
}

// ColourDifference between `colour` and the nearest blend of `a` and `b`: small on the mixed pixel of an edge
// between two colours, large on a structure of its own colour.
float DifferenceFromEveryBlend(const cv::Vec3f& colour, const cv::Vec3f& a, const cv::Vec3f& b) {
  const cv::Vec3f ab = b - a;
  const float length = ab.dot(ab);
  const float t = length > 0.0f ? std::clamp((colour - a).dot(ab) / length, 0.0f, 1.0f) : 0.0f;
  return ColourDifference(colour, a + t * ab);
}

// Walking from (x, y) along `step` for up to `reach` pixels, the colour of the first pixel of disparity at most
// `behind` whose colour differs from the starting pixel's; nothing if there is none.
std::optional<cv::Vec3f> SurfaceBehindOnThisSide(const DisparityMap& whole_patch, const cv::Mat& centre, int x, int y,
                                                 cv::Point2d step, float behind, const ThinStructureOptions& options) {
  const cv::Vec3f colour = centre.at<cv::Vec3f>(y, x);
  for (int k = 1; k <= options.reach; ++k) {
    const int xx = x + static_cast<int>(std::lround(k * step.x));
    const int yy = y + static_cast<int>(std::lround(k * step.y));
    if (xx < 0 || yy < 0 || xx >= whole_patch.width() || yy >= whole_patch.height()) return std::nullopt;
    const cv::Vec3f seen = centre.at<cv::Vec3f>(yy, xx);
    if (whole_patch.at(yy, xx) <= behind && ColourDifference(seen, colour) > options.colour_difference) return seen;
  }
  return std::nullopt;
}

// Whether the alternative's curve at (x, y) prefers the surface behind a thin structure the pixel belongs to.
bool ThinStructureInFront(const float* alternative, const DisparityMap& whole_patch,
                          const std::vector<float>& disparities, const cv::Mat& centre, int x, int y,
                          cv::Point2d normal, const ThinStructureOptions& options) {
  const int labels = static_cast<int>(disparities.size());
  const auto best = std::min_element(alternative, alternative + labels) - alternative;
  const float preferred = disparities[static_cast<std::size_t>(best)];
  if (!(preferred < whole_patch.at(y, x) - options.margin)) return false;
  const float behind = preferred + options.margin;
  const std::optional<cv::Vec3f> one_side = SurfaceBehindOnThisSide(whole_patch, centre, x, y, normal, behind, options);
  if (!one_side) return false;
  const std::optional<cv::Vec3f> other_side =
      SurfaceBehindOnThisSide(whole_patch, centre, x, y, -normal, behind, options);
  // An edge between two colours (a checker's) is not a structure: its mixed pixel is a blend of the two sides.
  return other_side &&
         DifferenceFromEveryBlend(centre.at<cv::Vec3f>(y, x), *one_side, *other_side) > options.blend_difference;
}

void CheckShapes(const CostVolume& cost, const OcclusionAlternatives& alternatives, const DisparityMap& whole_patch,
                 const std::vector<float>& disparities, const OcclusionMap& occlusion, const cv::Mat& centre) {
  const auto same_volume = [&](const CostVolume& other) {
    return other.width() == cost.width() && other.height() == cost.height() && other.labels() == cost.labels();
  };
  const auto same_image = [&](const cv::Mat& image) {
    return image.cols == cost.width() && image.rows == cost.height();
  };
  if (static_cast<int>(disparities.size()) != cost.labels())
    throw Error("depth: the occlusion alternatives' label count differs from the disparities'");
  if (!same_volume(alternatives.half) || !same_volume(alternatives.along) || whole_patch.width() != cost.width() ||
      whole_patch.height() != cost.height() || !same_image(centre) || !same_image(occlusion.candidate) ||
      !same_image(occlusion.along)) {
    throw Error("depth: occlusion alternatives, disparity, occlusion map, centre view and cost volume differ in size");
  }
  if (centre.type() != CV_32FC3 || occlusion.candidate.type() != CV_8U || occlusion.along.type() != CV_8U)
    throw Error("depth: occlusion alternatives need a float RGB centre view and an 8-bit occlusion map");
}

// The highest label a partial patch may stand in at, per pixel: the occluder horizon plus its slack (no limit
// without a horizon).
DisparityMap PartialPatchLimit(const DisparityMap& whole_patch, const OccluderHorizonOptions& horizon,
                               double longest_view_offset) {
  if (horizon.slack < 0.0f || !(longest_view_offset > 0.0))
    return DisparityMap(whole_patch.width(), whole_patch.height(), std::numeric_limits<float>::infinity());
  DisparityMap limit = OccluderHorizon(whole_patch, longest_view_offset, horizon.widening);
  limit.Mat() += horizon.slack;
  return limit;
}

}  // namespace

DisparityMap OccluderHorizon(const DisparityMap& whole_patch, double longest_view_offset, int widening) {
  if (!(longest_view_offset > 0.0)) throw Error("depth: the occluder horizon needs views off the centre");
  DisparityMap horizon = whole_patch;
  const int width = horizon.width();
  const int height = horizon.height();
  if (widening > 0) {
    cv::Mat values = horizon.Mat();
    cv::dilate(values, values,
               cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * widening + 1, 2 * widening + 1)));
  }
  // Two chamfer passes: each pixel takes the largest of its own value and its already visited neighbours' less the
  // fall over the step between them.
  const float straight = static_cast<float>(1.0 / longest_view_offset);
  const float diagonal = static_cast<float>(std::numbers::sqrt2 / longest_view_offset);
  const auto pass = [&](int y, int x, int step) {
    float value = horizon.at(y, x);
    const int xb = x - step;  // the neighbour already visited in this row
    const int yb = y - step;  // the row already visited
    if (xb >= 0 && xb < width) value = std::max(value, horizon.at(y, xb) - straight);
    if (yb >= 0 && yb < height) {
      value = std::max(value, horizon.at(yb, x) - straight);
      if (x - 1 >= 0) value = std::max(value, horizon.at(yb, x - 1) - diagonal);
      if (x + 1 < width) value = std::max(value, horizon.at(yb, x + 1) - diagonal);
    }
    horizon.at(y, x) = value;
  };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) pass(y, x, 1);
  for (int y = height - 1; y >= 0; --y)
    for (int x = width - 1; x >= 0; --x) pass(y, x, -1);
  return horizon;
}

int AdmitOcclusionAlternatives(CostVolume& cost, const OcclusionAlternatives& alternatives,
                               const DisparityMap& whole_patch, const std::vector<float>& disparities,
                               const OcclusionMap& occlusion, const cv::Mat& centre,
                               const ThinStructureOptions& options, const OccluderHorizonOptions& horizon,
                               double longest_view_offset) {
  const int width = cost.width();
  const int height = cost.height();
  const int labels = cost.labels();
  CheckShapes(cost, alternatives, whole_patch, disparities, occlusion, centre);
  const DisparityMap limit = PartialPatchLimit(whole_patch, horizon, longest_view_offset);
  int refused = 0;
#pragma omp parallel for schedule(static) reduction(+ : refused)
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (occlusion.candidate.at<unsigned char>(y, x) == 0) continue;
      const cv::Point2d normal = EdgeNormal(occlusion.along.at<unsigned char>(y, x));
      float* curve = cost.Curve(y, x);
      for (const CostVolume* alternative : {&alternatives.half, &alternatives.along}) {
        const float* partial_curve = alternative->Curve(y, x);
        if (!std::isfinite(partial_curve[0])) continue;  // not available here (e.g. the views along the edge are off)
        if (options.reach > 0 &&
            ThinStructureInFront(partial_curve, whole_patch, disparities, centre, x, y, normal, options)) {
          ++refused;
          continue;
        }
        const float highest = limit.at(y, x);
        for (int l = 0; l < labels; ++l)
          if (disparities[static_cast<std::size_t>(l)] < highest) curve[l] = std::min(curve[l], partial_curve[l]);
      }
    }
  }
  return refused;
}

}  // namespace lfsp::depth
