// Sub-label refinement, the weighted median, the slanted-plane fill and the textureless fill on inputs with known
// answers.

#include <gtest/gtest.h>

#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <string>

#include "lfsp/depth/cost_volume.h"
#include "lfsp/depth/plane_fit.h"
#include "lfsp/depth/refinement.h"
#include "lfsp/depth/textureless_fill.h"

namespace lfsp::depth {
namespace {

TEST(SelectDisparity, ParabolaRefinementFindsTheTrueMinimumBetweenLabels) {
  const std::vector<float> labels = LabelDisparities(-1.0f, 1.0f, 21);  // step 0.1
  CostVolume cost(4, 3, 21);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 4; ++x) {
      const float minimum = 7.0f + 0.1f * static_cast<float>(x) + 0.2f * static_cast<float>(y);  // label units
      for (int l = 0; l < 21; ++l) {
        const float t = static_cast<float>(l) - minimum;
        cost.Curve(y, x)[l] = 1.0f + 0.05f * t * t;
      }
    }
  }
  const DisparityEstimate estimate = SelectDisparity(cost, labels);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 4; ++x) {
      const float expected = -1.0f + 0.1f * (7.0f + 0.1f * static_cast<float>(x) + 0.2f * static_cast<float>(y));
      EXPECT_NEAR(estimate.disparity.at(y, x), expected, 1e-4);
      EXPECT_GT(estimate.confidence.at(y, x), 0.0f);
      EXPECT_LE(estimate.confidence.at(y, x), 1.0f);
    }
  }
  // A flat curve has no confidence.
  CostVolume flat(1, 1, 21, 0.5f);
  EXPECT_FLOAT_EQ(SelectDisparity(flat, labels).confidence.at(0, 0), 0.0f);
}

// A textured fronto-parallel surface 0.375 label steps from a label: the truncated L1 data cost rises linearly on
// both sides of the true minimum, and semi-global aggregation adds p1 per path to the labels next to the best one
// whatever the offset. The parabola through the aggregated costs then lands much nearer the label; the equiangular
// fit through the data cost summed over the window reads the truth.
TEST(SubLabelFromData, ReadsAFrontoParallelSurfaceBetweenLabelsWhereTheAggregatedParabolaIsPulledToTheLabel) {
  const std::vector<float> labels = LabelDisparities(-1.0f, 1.0f, 21);  // step 0.1
  constexpr int kSize = 12;
  constexpr float kMinimum = 7.375f;  // label units: disparity -0.2625
  constexpr float kPenalty = 0.5f;    // p1 per path, 8 paths
  CostVolume data(kSize, kSize, 21), aggregated(kSize, kSize, 21);
  cv::Mat guide(kSize, kSize, CV_32FC3, cv::Scalar(0.4, 0.5, 0.3));
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const float slope = 0.5f + 0.05f * static_cast<float>((x * 7 + y * 3) % 5);  // texture varies by pixel
      for (int l = 0; l < 21; ++l) {
        const float c = slope * std::abs(static_cast<float>(l) - kMinimum);
        data.Curve(y, x)[l] = c;
        aggregated.Curve(y, x)[l] = 8.0f * c + (l == 7 ? 0.0f : 8.0f * kPenalty);
      }
    }
  const float truth = -1.0f + 0.1f * kMinimum;
  DisparityEstimate estimate = SelectDisparity(aggregated, labels);
  EXPECT_GT(std::abs(estimate.disparity.at(5, 5) - truth), 0.01f);  // the pull this refinement removes
  RefineSubLabelFromData(estimate.disparity, aggregated, data, labels, guide,
                         SubLabelOptions{3, 0.05f, 0.75f, kPenalty});
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) EXPECT_NEAR(estimate.disparity.at(y, x), truth, 1e-4) << x << ", " << y;
  // Off: the aggregated cost's parabola stays.
  const float parabola = SelectDisparity(aggregated, labels).disparity.at(5, 5);
  DisparityEstimate off = SelectDisparity(aggregated, labels);
  RefineSubLabelFromData(off.disparity, aggregated, data, labels, guide, SubLabelOptions{0, 0.05f, 0.75f, kPenalty});
  // Where the paths add less than the saturation (they carry the neighbours' data): the parabola stays too.
  DisparityEstimate unsaturated = SelectDisparity(aggregated, labels);
  RefineSubLabelFromData(unsaturated.disparity, aggregated, data, labels, guide,
                         SubLabelOptions{3, 0.05f, 0.75f, 2.0f * kPenalty});
  EXPECT_FLOAT_EQ(unsaturated.disparity.at(5, 5), parabola);
  EXPECT_FLOAT_EQ(off.disparity.at(5, 5), parabola);
}

// A flat blue region beside a thin brown bar in front (2 px), whose disparity the semi-global pass spread over a
// 14 x 14 block of the region: the fine window cannot outvote the block, the wide one does. The bar keeps its
// disparity, and a textured slanted plane below (a slope the wide window would bias by more than 0.07 px) keeps
// the fine median's values.
TEST(WeightedMedian, TheWideWindowTakesBackAFlatRegionAThinBarSpreadOver) {
  constexpr int kSize = 96;
  constexpr float kBar = 1.2f, kRegion = 0.1f;
  const cv::Vec3f blue(0.2f, 0.2f, 0.6f), brown(0.5f, 0.3f, 0.1f);
  cv::Mat guide(kSize, kSize, CV_32FC3);
  DisparityMap disparity(kSize, kSize);
  const auto slanted = [](int x, int y) { return 0.04f * static_cast<float>(x) + 0.01f * static_cast<float>(y); };
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const bool textured = y >= 64;
      const bool bar = (x == 40 || x == 41) && !textured;
      // Bands of two greys, 24 px wide: near a band's edge, a wide window holds much more of its band on one side.
      const float grey = (x / 24) % 2 == 0 ? 0.3f : 0.7f;
      guide.at<cv::Vec3f>(y, x) = bar ? brown : textured ? cv::Vec3f(grey, grey, grey) : blue;
      disparity.at(y, x) = bar ? kBar : textured ? slanted(x, y) : kRegion;
    }
  }
  for (int y = 20; y < 34; ++y) {
    for (int x = 42; x < 56; ++x) disparity.at(y, x) = kBar;  // the spread, right of the bar
  }
  DisparityMap fine_only = disparity;
  MedianOptions fine;
  fine.wide_radius = 0;
  WeightedMedianRefine(fine_only, guide, fine);
  DisparityMap both = disparity;
  WeightedMedianRefine(both, guide, MedianOptions{});
  EXPECT_FLOAT_EQ(fine_only.at(27, 49), kBar) << "the block's middle outvotes the fine window";
  for (int y = 20; y < 34; ++y) {
    for (int x = 42; x < 56; ++x) EXPECT_FLOAT_EQ(both.at(y, x), kRegion) << "at " << x << ", " << y;
  }
  for (int y = 0; y < 60; ++y) {
    EXPECT_FLOAT_EQ(both.at(y, 40), kBar);
    EXPECT_FLOAT_EQ(both.at(y, 41), kBar);
  }
  for (int y = 70; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) EXPECT_FLOAT_EQ(both.at(y, x), fine_only.at(y, x)) << "at " << x << ", " << y;
  }
  // Taken everywhere (a threshold of 1e-6 px), the wide window biases the slanted plane: why it is held to gross
  // errors.
  DisparityMap everywhere = disparity;
  MedianOptions wide_everywhere;
  wide_everywhere.wide_threshold = 1e-6f;
  WeightedMedianRefine(everywhere, guide, wide_everywhere);
  double worst = 0.0;
  for (int y = 70; y < kSize - 12; ++y) {
    for (int x = 12; x < kSize - 12; ++x) {
      worst = std::max(worst, std::abs(double{everywhere.at(y, x)} - slanted(x, y)));
    }
  }
  RecordProperty("wide_everywhere_worst_px", std::to_string(worst));
  EXPECT_GT(worst, 0.07);
}

// Non-finite disparities (a hostile input's NaN views can make them) are left out of both windows, so the
// median neither breaks its sort nor spreads them: a NaN block in a plane takes the plane's value.
TEST(WeightedMedian, LeavesNonFiniteDisparitiesOut) {
  DisparityMap disparity(32, 32, 0.5f);
  for (int y = 10; y < 13; ++y) {
    for (int x = 10; x < 13; ++x) disparity.at(y, x) = std::numeric_limits<float>::quiet_NaN();
  }
  disparity.at(20, 20) = std::numeric_limits<float>::infinity();
  const cv::Mat guide(32, 32, CV_32FC3, cv::Scalar(0.4, 0.4, 0.4));
  WeightedMedianRefine(disparity, guide, MedianOptions{});
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) EXPECT_FLOAT_EQ(disparity.at(y, x), 0.5f) << "at " << x << ", " << y;
  }
}

TEST(PlaneFit, UnsupportedPixelsTakeTheirSuperpixelsPlane) {
  // One slanted plane over a plain grey image; a block of wrong, unsupported values inside it.
  const int size = 64;
  DisparityMap disparity(size, size);
  DisparityMap support(size, size, 1.0f);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) disparity.at(y, x) = 0.01f * static_cast<float>(x) - 0.02f * static_cast<float>(y);
  }
  for (int y = 20; y < 28; ++y) {
    for (int x = 30; x < 38; ++x) {
      disparity.at(y, x) = 5.0f;
      support.at(y, x) = 0.0f;
    }
  }
  const cv::Mat guide(size, size, CV_32FC3, cv::Scalar(0.4, 0.4, 0.4));
  PlaneFitRefine(disparity, support, guide, {});
  for (int y = 20; y < 28; ++y) {
    for (int x = 30; x < 38; ++x) {
      EXPECT_NEAR(disparity.at(y, x), 0.01f * static_cast<float>(x) - 0.02f * static_cast<float>(y), 1e-3);
    }
  }
}

// A checkerboard of flat tiles, 24 px each, two colours 0.3 apart: only the pixels within two of a tile edge have
// texture (the 3 x 3 mean of the squared gradient reaches that far).
cv::Mat FlatTiles(int width, int height) {
  cv::Mat guide(height, width, CV_32FC3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float level = ((x / 24 + y / 24) % 2 == 0) ? 0.3f : 0.6f;
      guide.at<cv::Vec3f>(y, x) = cv::Vec3f(level, level, level);
    }
  return guide;
}

// A floor sloping down the picture: the tile rims read it right, the flat interiors of the tiles away from the
// picture's border as a staircase of 0.1 px treads (what the semi-global pass leaves there). The fill puts the
// interiors back on the plane. (Along the picture's border a tile has no rim, and the fill levels it out there.)
TEST(TexturelessFill, FlatTilesOfASlopedFloorTakeThePlaneTheirRimsRead) {
  const int width = 120, height = 96;
  const cv::Mat guide = FlatTiles(width, height);
  const auto truth = [](int x, int y) { return 0.004f * static_cast<float>(x) + 0.01f * static_cast<float>(y) - 0.5f; };
  const auto on_rim = [](int t) { return t % 24 <= 1 || t % 24 >= 22; };
  const auto inner_tile = [&](int x, int y) { return x >= 24 && x < width - 24 && y >= 24 && y < height - 24; };
  DisparityMap disparity(width, height);
  float staircase_error = 0.0f;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const bool tread = inner_tile(x, y) && !on_rim(x) && !on_rim(y);
      disparity.at(y, x) = tread ? std::round(truth(x, y) * 10.0f) / 10.0f : truth(x, y);
      staircase_error = std::max(staircase_error, std::abs(disparity.at(y, x) - truth(x, y)));
    }
  ASSERT_GT(staircase_error, 0.045f);
  FillTexturelessDisparity(disparity, guide);
  float inner_error = 0.0f;
  for (int y = 24; y < height - 24; ++y)
    for (int x = 24; x < width - 24; ++x)
      inner_error = std::max(inner_error, std::abs(disparity.at(y, x) - truth(x, y)));
  EXPECT_LT(inner_error, 0.003f);
}

// The fill's energy as textureless_fill.h defines it, minimised exactly (sparse Cholesky): each pixel's own weight
// from the centre view's gradient (central differences, 0 at the border; summed over channels; 3 x 3 mean with the
// border mirrored), the pairs whose disparities differ by at most `jump`.
DisparityMap ExactFill(const DisparityMap& given, const cv::Mat& guide, const TexturelessFillOptions& options) {
  const int width = given.width(), height = given.height();
  const auto index = [&](int x, int y) { return y * width + x; };
  const auto mirror = [](int t, int n) { return t < 0 ? -t : (t >= n ? 2 * n - 2 - t : t); };
  std::vector<double> energy(static_cast<std::size_t>(width * height), 0.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const cv::Vec3f gx =
          (guide.at<cv::Vec3f>(y, mirror(x + 1, width)) - guide.at<cv::Vec3f>(y, mirror(x - 1, width))) * 0.5f;
      const cv::Vec3f gy =
          (guide.at<cv::Vec3f>(mirror(y + 1, height), x) - guide.at<cv::Vec3f>(mirror(y - 1, height), x)) * 0.5f;
      energy[index(x, y)] = gx.dot(gx) + gy.dot(gy);
    }
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd target(width * height);
  std::vector<double> diagonal(static_cast<std::size_t>(width * height), 0.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double sum = 0.0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) sum += energy[index(mirror(x + dx, width), mirror(y + dy, height))];
      const double e = sum / 9.0;
      const double own = e / (e + options.texture_scale * options.texture_scale) + 1e-6;
      diagonal[index(x, y)] += own;
      target(index(x, y)) = own * given.at(y, x);
      for (const auto& [nx, ny] : {std::pair{x + 1, y}, std::pair{x, y + 1}}) {
        if (nx >= width || ny >= height || std::abs(given.at(y, x) - given.at(ny, nx)) > options.jump) continue;
        diagonal[index(x, y)] += options.smoothness;
        diagonal[index(nx, ny)] += options.smoothness;
        entries.emplace_back(index(x, y), index(nx, ny), -options.smoothness);
        entries.emplace_back(index(nx, ny), index(x, y), -options.smoothness);
      }
    }
  for (int i = 0; i < width * height; ++i) entries.emplace_back(i, i, diagonal[static_cast<std::size_t>(i)]);
  Eigen::SparseMatrix<double> normal(width * height, width * height);
  normal.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  const Eigen::VectorXd solution = solver.solve(target);
  DisparityMap exact(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) exact.at(y, x) = static_cast<float>(solution(index(x, y)));
  return exact;
}

// Flat tiles four times wider than above, on a picture of odd size: values must travel far across the flat
// regions, which only the coarse levels carry, and blocks at the odd edges hold fewer pixels. The approximate
// solution stays within 3e-3 px of the exact minimum (without the coarse levels, about 0.1 off).
TEST(TexturelessFill, ApproachesTheExactMinimumAcrossWideFlatRegions) {
  const int width = 389, height = 263, tile = 96;
  cv::Mat guide(height, width, CV_32FC3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float level = ((x / tile + y / tile) % 2 == 0) ? 0.3f : 0.6f;
      guide.at<cv::Vec3f>(y, x) = cv::Vec3f(level, 0.8f * level, 0.5f * level);
    }
  DisparityMap given(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float truth = 0.002f * static_cast<float>(x) + 0.004f * static_cast<float>(y) - 0.6f;
      const bool rim = x % tile <= 1 || x % tile >= tile - 2 || y % tile <= 1 || y % tile >= tile - 2;
      given.at(y, x) = rim ? truth : std::round(truth * 10.0f) / 10.0f;
    }
  given.at(150, 200) = 0.7f;  // a depth step around one pixel: cut off from its neighbours
  const DisparityMap exact = ExactFill(given, guide, {});
  DisparityMap filled = given;
  FillTexturelessDisparity(filled, guide);
  float largest = 0.0f, moved = 0.0f;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      largest = std::max(largest, std::abs(filled.at(y, x) - exact.at(y, x)));
      moved = std::max(moved, std::abs(filled.at(y, x) - given.at(y, x)));
    }
  EXPECT_LT(largest, 3e-3f);
  EXPECT_GT(moved, 0.05f);  // the fill did change the staircase
}

// A non-finite disparity stays as it is and changes nothing around it.
TEST(TexturelessFill, LeavesNonFiniteDisparitiesAloneAndOut) {
  const int width = 120, height = 96;
  const cv::Mat guide = FlatTiles(width, height);
  DisparityMap given(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) given.at(y, x) = std::round((0.01f * static_cast<float>(y) - 0.3f) * 10.0f) / 10.0f;
  DisparityMap clean = given;
  FillTexturelessDisparity(clean, guide);
  DisparityMap holed = given;
  holed.at(50, 60) = std::numeric_limits<float>::quiet_NaN();
  holed.at(10, 10) = std::numeric_limits<float>::infinity();
  FillTexturelessDisparity(holed, guide);
  EXPECT_TRUE(std::isnan(holed.at(50, 60)));
  EXPECT_TRUE(std::isinf(holed.at(10, 10)));
  float largest = 0.0f;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (std::isfinite(holed.at(y, x))) largest = std::max(largest, std::abs(holed.at(y, x) - clean.at(y, x)));
  EXPECT_LT(largest, 0.02f);  // the two holes' neighbours lose one pair each, nothing more
}

// Two objects of one colour, one in front of the other: nothing tells them apart but the disparity, whose step
// must stay where it is.
TEST(TexturelessFill, KeepsADepthStepThatHasNoColourEdge) {
  const int width = 64, height = 48;
  const cv::Mat guide(height, width, CV_32FC3, cv::Scalar(0.5f, 0.4f, 0.3f));
  DisparityMap disparity(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) disparity.at(y, x) = x < 30 ? 1.2f : 0.1f;
  FillTexturelessDisparity(disparity, guide);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) ASSERT_NEAR(disparity.at(y, x), x < 30 ? 1.2f : 0.1f, 1e-4) << x << ", " << y;
}

// Where every pixel has texture, each keeps its own disparity: the smoothness weighs a thousandth of it.
TEST(TexturelessFill, TexturedPixelsKeepTheirDisparity) {
  const int width = 64, height = 48;
  cv::Mat guide(height, width, CV_32FC3);
  cv::RNG rng(7);
  rng.fill(guide, cv::RNG::UNIFORM, 0.0, 1.0);
  DisparityMap disparity(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) disparity.at(y, x) = static_cast<float>(rng.uniform(-0.1, 0.1));
  const DisparityMap given = disparity;
  FillTexturelessDisparity(disparity, guide);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) ASSERT_NEAR(disparity.at(y, x), given.at(y, x), 2e-3) << x << ", " << y;
  // Off, nothing moves at all.
  DisparityMap untouched = given;
  FillTexturelessDisparity(untouched, FlatTiles(width, height), TexturelessFillOptions{.smoothness = 0.0f});
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) ASSERT_EQ(untouched.at(y, x), given.at(y, x));
}

}  // namespace
}  // namespace lfsp::depth
