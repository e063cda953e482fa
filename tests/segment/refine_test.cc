// Unit tests of segment/src/refine.h (issue 14 item 5): RefineLabels, the block-coordinate descent of Eq. 3 that
// moves boundary rays to the cheapest neighbouring label. The light fields are tiny (1x1 or 3x3 views of 8x4 or 8x5
// pixels) with constant-colour regions (Lab L only) and known disparities, so the cost of each candidate label can
// be worked out by hand from the energy in lfsp/segment/params.h:
//   E = |Lab - mean|^2 / colour_scale^2 + lambda_p |p - centroid|^2 / size^2 + lambda_d ((d - plane) / range)^2
//       + lambda_b / 8 * (differing spatial neighbours * pen_spatial + angular * pen_angular + mixed * pen_mixed).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/segment/params.h"
#include "lfsp/segment/plane.h"
#include "refine.h"

namespace lfsp::segment {
namespace {

// A light field of nu x nv views with its Lab buffer, centre disparity, labels and planes.
struct Field {
  LightFieldShape shape;
  std::vector<float> lab;
  std::vector<float> disparity;  // centre view
  Labels labels;
  std::vector<Plane> planes;

  Field(int views, int width, int height, int superpixels)
      : shape{views, views, width, height, 3},
        lab(shape.Views() * shape.ViewPixels() * 3, 0.0f),
        disparity(shape.ViewPixels(), 0.0f),
        labels(shape, 0),
        planes(static_cast<std::size_t>(superpixels)) {}

  void SetL(ViewIndex view, int x, int y, float l) {
    const std::size_t cam = static_cast<std::size_t>(CameraNumber(view, shape.nu));
    lab[(cam * shape.ViewPixels() + static_cast<std::size_t>(y * shape.width + x)) * 3] = l;
  }
  void SetDisparity(int x, int y, float d) { disparity[static_cast<std::size_t>(y * shape.width + x)] = d; }

  // Every view's labels as one string per view row, views in camera order separated by '|', for readable failures.
  std::string LabelsText() const {
    std::string text;
    for (int v = 0; v < shape.nv; ++v)
      for (int u = 0; u < shape.nu; ++u) {
        if (!text.empty()) text += " | ";
        for (int y = 0; y < shape.height; ++y) {
          if (y > 0) text += "/";
          for (int x = 0; x < shape.width; ++x) text += std::to_string(labels.at({u, v}, y, x));
        }
      }
    return text;
  }

  RefineReport Refine(const LfspParams& params, double disparity_range = 1.0) {
    RefineInputs inputs;
    inputs.lab = lab.data();
    inputs.centre_disparity = disparity.data();
    inputs.disparity_range = disparity_range;
    inputs.superpixels = static_cast<int>(planes.size());
    return RefineLabels(inputs, params, labels, planes);
  }
};

LfspParams Params() {
  LfspParams params;  // Table II weights, colour_scale 7.0711, size 20
  params.iterations = 5;
  params.plane_iterations = 2;
  params.threads = 1;
  return params;
}

constexpr float kDark = 30.0f,
                kLight = 70.0f;  // 40 Lab units apart: 32 units of colour energy, above any boundary cost

// 3x3 views of 8x4 where the scene is a dark background (d = 0) on the left and a light foreground (d = fg) on the
// right: in view (u, v) the foreground covers x >= 4 - du * fg. Labels start as the centre's in every view, with the
// boundary moved by `shift` columns to the right (column 4 .. 4 + shift - 1 wrongly label 0).
Field TwoRegions(int fg, int shift) {
  Field field(3, 8, 4, 2);
  const ViewIndex c = field.shape.Centre();
  for (int v = 0; v < 3; ++v)
    for (int u = 0; u < 3; ++u)
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) {
          const bool foreground = x >= 4 - (u - c.u) * fg;
          field.SetL({u, v}, x, y, foreground ? kLight : kDark);
          field.labels.at({u, v}, y, x) = x >= 4 + shift ? 1 : 0;
        }
  for (int y = 0; y < 4; ++y)
    for (int x = 4; x < 8; ++x) field.SetDisparity(x, y, static_cast<float>(fg));
  field.planes[0] = {0.0, 0.0, 0.0};
  field.planes[1] = {0.0, 0.0, static_cast<double>(fg)};
  return field;
}

int ExpectedTwoRegionLabel(int fg, int u, int x) { return x >= 4 - (u - 1) * fg ? 1 : 0; }

TEST(RefineLabels, WronglyLabelledRaysMoveToTheLabelOfTheirColourInEveryView) {
  Field field = TwoRegions(0, 1);
  const RefineReport report = field.Refine(Params());
  for (int v = 0; v < 3; ++v)
    for (int u = 0; u < 3; ++u)
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
          ASSERT_EQ(field.labels.at({u, v}, y, x), ExpectedTwoRegionLabel(0, u, x))
              << "view " << u << "," << v << " ray " << x << "," << y << ": " << field.LabelsText();
  // The 4 rays of column 4 in each of the 9 views move once; the second sweep finds nothing and stops.
  EXPECT_EQ(report.moves, 36);
  EXPECT_EQ(report.moves_per_iteration, (std::vector<long long>{36, 0}));
  EXPECT_EQ(report.iterations, 2);
  EXPECT_EQ(report.occlusion_boundaries + report.hinge_boundaries + report.coplanar_boundaries, 1);
}

TEST(RefineLabels, SideViewLabelsFollowTheForegroundDisparity) {
  // Foreground d = 1: it sits one column further left in the views u = 2 and one further right in u = 0 than in the
  // centre, while the labels start as the centre's everywhere. The 3 + 3 side views each have 4 wrong rays.
  Field field = TwoRegions(1, 0);
  const RefineReport report = field.Refine(Params());
  for (int v = 0; v < 3; ++v)
    for (int u = 0; u < 3; ++u)
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
          ASSERT_EQ(field.labels.at({u, v}, y, x), ExpectedTwoRegionLabel(1, u, x))
              << "view " << u << "," << v << " ray " << x << "," << y << ": " << field.LabelsText();
  EXPECT_EQ(report.moves, 24);
  // The centre view did not change, so neither did the planes fitted to its exact disparity.
  EXPECT_NEAR(field.planes[0].c, 0.0, 1e-9);
  EXPECT_NEAR(field.planes[1].c, 1.0, 1e-9);
  EXPECT_NEAR(field.planes[1].a, 0.0, 1e-9);
  EXPECT_EQ(report.occlusion_boundaries, 1);  // a step of 1 between planes: occlusion 0.25 < coplanar 1
}

// The TwoRegions scene with d = 1 but one colour everywhere, every view labelled right except the corner view
// (2, 0), which has the centre's labels: its column 3 (foreground there) is wrongly label 0. Only the clique can
// tell. For a ray (3, y) of that view, label 1 (d = 1) meets its angular neighbours where the convention puts them:
// (4, y) in views (1, 0) and (1, 1), (3, y - 1) in view (2, 1), all label 1; label 0 (d = 0) finds label 1 at (3, y)
// in view (2, 1), 1 of 3 differing, worth 8/3 * pen_angular / 8. Spatially label 1 costs 2/8 more; position and
// colour are even.
Field OneWrongSideView() {
  Field field = TwoRegions(1, 0);
  for (int v = 0; v < 3; ++v)
    for (int u = 0; u < 3; ++u)
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) {
          field.SetL({u, v}, x, y, 50.0f);
          field.labels.at({u, v}, y, x) = ExpectedTwoRegionLabel(1, u, x);
        }
  for (int y = 0; y < 4; ++y) field.labels.at({2, 0}, y, 3) = 0;
  return field;
}

TEST(RefineLabels, TheAngularTermPullsASideViewIntoAgreementAlongTheDisparity) {
  Field field = OneWrongSideView();
  LfspParams params = Params();
  params.pen_mixed = 0.0;  // isolate the angular neighbours
  const RefineReport report = field.Refine(params);
  for (int v = 0; v < 3; ++v)
    for (int u = 0; u < 3; ++u)
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
          ASSERT_EQ(field.labels.at({u, v}, y, x), ExpectedTwoRegionLabel(1, u, x))
              << "view " << u << "," << v << " ray " << x << "," << y << ": " << field.LabelsText();
  EXPECT_EQ(report.moves, 4);
}

TEST(RefineLabels, WithoutCliquePenaltiesAcrossViewsTheWrongSideViewStays) {
  Field field = OneWrongSideView();
  LfspParams params = Params();
  params.pen_mixed = 0.0;
  params.pen_angular = 0.0;  // only the spatial neighbours remain, and they favour the current boundary
  const RefineReport report = field.Refine(params);
  EXPECT_EQ(report.moves, 0) << field.LabelsText();
  for (int y = 0; y < 4; ++y) EXPECT_EQ(field.labels.at({2, 0}, y, 3), 0);
}

TEST(RefineLabels, ConvergenceZeroRunsEveryIteration) {
  Field field = TwoRegions(0, 1);
  LfspParams params = Params();
  params.convergence = 0.0;  // fewer than 0 moves never happens
  params.iterations = 4;
  const RefineReport report = field.Refine(params);
  EXPECT_EQ(report.iterations, 4);
  EXPECT_EQ(report.moves_per_iteration, (std::vector<long long>{36, 0, 0, 0}));
  EXPECT_EQ(report.sweep_seconds.size(), 4u);
}

TEST(RefineLabels, ALooseConvergenceStopsAfterTheFirstIteration) {
  Field field = TwoRegions(0, 1);
  LfspParams params = Params();
  params.convergence = 0.2;  // 36 moves of 288 rays = 0.125 < 0.2
  const RefineReport report = field.Refine(params);
  EXPECT_EQ(report.iterations, 1);
  EXPECT_EQ(report.moves, 36);
  params.convergence = 0.1;  // 0.125 >= 0.1: a second iteration runs (and finds nothing)
  Field again = TwoRegions(0, 1);
  EXPECT_EQ(again.Refine(params).iterations, 2);
}

TEST(RefineLabels, ZeroIterationsLeaveTheLabelsAlone) {
  Field field = TwoRegions(0, 1);
  const Labels before = field.labels;
  LfspParams params = Params();
  params.iterations = 0;
  const RefineReport report = field.Refine(params);
  EXPECT_EQ(report.iterations, 0);
  EXPECT_EQ(report.moves, 0);
  EXPECT_TRUE(std::equal(before.data(), before.data() + before.size(), field.labels.data()));
}

// One view (the centre) of 8x4: label 0 on columns 0..3, label 1 on 4..7. Column 3 has label 1's colour but label
// 0's disparity (plane 0: d = 0, plane 1: d = 1, range 1).
Field ColourAgainstDisparity() {
  Field field(1, 8, 4, 2);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      field.SetL({0, 0}, x, y, x >= 3 ? 60.0f : 50.0f);
      field.SetDisparity(x, y, x >= 4 ? 1.0f : 0.0f);
      field.labels.at({0, 0}, y, x) = x >= 4 ? 1 : 0;
    }
  field.planes[0] = {0.0, 0.0, 0.0};
  field.planes[1] = {0.0, 0.0, 1.0};
  return field;
}

TEST(RefineLabels, TheDisparityTermHoldsARayOnItsPlane) {
  // Column 3 against label 1: colour saves (0.75 * 10)^2 / 50 = 1.1, the disparity term costs lambda_d * 1 = 50.
  Field field = ColourAgainstDisparity();
  const RefineReport report = field.Refine(Params());
  EXPECT_EQ(report.moves, 0) << field.LabelsText();
  for (int y = 0; y < 4; ++y) EXPECT_EQ(field.labels.at({0, 0}, y, 3), 0);
}

TEST(RefineLabels, WithoutTheDisparityTermColourWins) {
  Field field = ColourAgainstDisparity();
  LfspParams params = Params();
  params.lambda_d = 0.0;
  const RefineReport report = field.Refine(params);
  EXPECT_EQ(report.moves, 4) << field.LabelsText();
  for (int y = 0; y < 4; ++y) {
    EXPECT_EQ(field.labels.at({0, 0}, y, 2), 0);
    EXPECT_EQ(field.labels.at({0, 0}, y, 3), 1);
  }
}

// One view of 8x4 on one plane (d = 0): label 0 dark on columns 0..3, label 1 five Lab units lighter on 4..7, and the
// ray (3, 1) of label 0 has label 1's colour. Moving it saves (15/16 * 5)^2 / 50 = 0.44 of colour and costs
// 0.02 of position plus lambda_b * 2 / 8 (5 of its 8 neighbours differ from label 1, 3 from label 0).
Field OneOddRay() {
  Field field(1, 8, 4, 2);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      field.SetL({0, 0}, x, y, x >= 4 ? 55.0f : 50.0f);
      field.labels.at({0, 0}, y, x) = x >= 4 ? 1 : 0;
    }
  field.SetL({0, 0}, 3, 1, 55.0f);
  return field;
}

TEST(RefineLabels, ALowBoundaryWeightLetsAnOddRayFollowItsColour) {
  Field field = OneOddRay();
  LfspParams params = Params();
  params.lambda_b = 1.0;  // 0.02 + 0.25 < 0.44
  const RefineReport report = field.Refine(params);
  EXPECT_EQ(report.moves, 1) << field.LabelsText();
  EXPECT_EQ(field.labels.at({0, 0}, 1, 3), 1);
}

TEST(RefineLabels, AHighBoundaryWeightKeepsTheBoundaryStraight) {
  Field field = OneOddRay();
  LfspParams params = Params();
  params.lambda_b = 4.0;  // 0.02 + 1.0 > 0.44
  const RefineReport report = field.Refine(params);
  EXPECT_EQ(report.moves, 0) << field.LabelsText();
  EXPECT_EQ(field.labels.at({0, 0}, 1, 3), 0);
}

TEST(RefineLabels, APositionWeightHoldsTheOddRayToItsCentroid) {
  // lambda_p 2 -> 120 makes the position difference (6.5 - 2.5) * lambda_p / 400 = 1.2 > 0.44 - 0.25.
  Field field = OneOddRay();
  LfspParams params = Params();
  params.lambda_b = 1.0;
  params.lambda_p = 120.0;
  const RefineReport report = field.Refine(params);
  EXPECT_EQ(field.labels.at({0, 0}, 1, 3), 0) << field.LabelsText();
  EXPECT_EQ(report.moves, 0);
}

// One view of 8x4: label 0 dark on columns 0..3, label 1 light on 4..7, and label 2 light on `rays` rays of column 4
// from row 1 down. With lambda_b 8 a ray of label 2 pays 8 * (differing neighbours) / 8 and would rather be label 1.
Field SmallLabel(int rays) {
  Field field(1, 8, 4, 3);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      field.SetL({0, 0}, x, y, x >= 4 ? kLight : kDark);
      field.labels.at({0, 0}, y, x) = x >= 4 ? 1 : 0;
    }
  for (int y = 1; y < 1 + rays; ++y) field.labels.at({0, 0}, y, 4) = 2;
  return field;
}

TEST(RefineLabels, TheLastCentreRayOfALabelIsNeverMoved) {
  Field field = SmallLabel(1);
  LfspParams params = Params();
  params.lambda_b = 8.0;  // label 2 costs 8 (all 8 neighbours differ), label 1 costs 3 (three label-0 neighbours)
  const RefineReport report = field.Refine(params);
  EXPECT_EQ(field.labels.at({0, 0}, 1, 4), 2) << field.LabelsText();
  EXPECT_EQ(report.moves, 0);
}

TEST(RefineLabels, ALabelOfTwoCentreRaysLosesOneButKeepsTheOther) {
  // The control of the test above: with two rays, (4, 1) is scanned first and moves to label 1 (label 2 would cost
  // 7, label 1 costs 4); then (4, 2) is label 2's last ray and stays.
  Field field = SmallLabel(2);
  LfspParams params = Params();
  params.lambda_b = 8.0;
  const RefineReport report = field.Refine(params);
  EXPECT_EQ(field.labels.at({0, 0}, 1, 4), 1) << field.LabelsText();
  EXPECT_EQ(field.labels.at({0, 0}, 2, 4), 2);
  EXPECT_EQ(report.moves, 1);
}

TEST(RefineLabels, ARayWhoseRemovalWouldSplitItsSliceStays) {
  // One view of 8x5. Label 0 is a dumbbell: columns 0..2 and 5..7 joined by the bridge (3, 2), (4, 2); label 1 is
  // the 2x2 blocks above and below the bridge. The bridge and the ray (2, 0) have label 1's colour. (2, 0) moves;
  // the bridge rays would cut label 0 in two and stay.
  const std::vector<std::string> rows{"00011000", "00011000", "00000000", "00011000", "00011000"};
  Field field(1, 8, 5, 2);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 8; ++x) {
      const int label = rows[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)] - '0';
      field.labels.at({0, 0}, y, x) = label;
      field.SetL({0, 0}, x, y, label == 1 ? kLight : kDark);
    }
  field.SetL({0, 0}, 3, 2, kLight);
  field.SetL({0, 0}, 4, 2, kLight);
  field.SetL({0, 0}, 2, 0, kLight);
  const RefineReport report = field.Refine(Params());
  EXPECT_EQ(field.labels.at({0, 0}, 0, 2), 1) << field.LabelsText();
  EXPECT_EQ(field.labels.at({0, 0}, 2, 3), 0);
  EXPECT_EQ(field.labels.at({0, 0}, 2, 4), 0);
  EXPECT_EQ(report.moves, 1);
}

}  // namespace
}  // namespace lfsp::segment
