#include "lfsp/core/registration.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/parallel_for.h"
#include "lfsp/core/srgb.h"
#include "lfsp/core/srgb_table.h"
#include "lfsp/core/view_crop.h"

namespace lfsp {

namespace {

// One least-squares step: the translation, gain and offset taking `reference` to `moving`, to first order.
// The normal matrix is symmetric and its last unknown's coefficient is 1: its ten distinct entries are summed as
// scalars, each as the same products in the same order as the whole 4x4 outer product was (the same doubles), in
// a third of the time.
cv::Vec4d LinearisedStep(const cv::Mat& reference, const cv::Mat& moving, int margin, const cv::Mat& mask) {
  // Unknowns: dx, dy, gain - 1, offset. moving - reference = -gx dx - gy dy + reference (gain - 1) + offset.
  double n00 = 0, n01 = 0, n02 = 0, n03 = 0, n11 = 0, n12 = 0, n13 = 0, n22 = 0, n23 = 0, n33 = 0;
  double r0 = 0, r1 = 0, r2 = 0, r3 = 0;
  for (int y = margin; y < reference.rows - margin; ++y) {
    const float* up = reference.ptr<float>(y - 1);
    const float* row = reference.ptr<float>(y);
    const float* down = reference.ptr<float>(y + 1);
    const float* other = moving.ptr<float>(y);
    const unsigned char* used = mask.empty() ? nullptr : mask.ptr<unsigned char>(y);
    for (int x = margin; x < reference.cols - margin; ++x) {
      if (used != nullptr && used[x] == 0) continue;
      const double a0 = -0.5 * (row[x + 1] - row[x - 1]), a1 = -0.5 * (down[x] - up[x]), a2 = row[x];
      const double b = other[x] - row[x];
      n00 += a0 * a0;
      n01 += a0 * a1;
      n02 += a0 * a2;
      n03 += a0 * 1.0;
      n11 += a1 * a1;
      n12 += a1 * a2;
      n13 += a1 * 1.0;
      n22 += a2 * a2;
      n23 += a2 * 1.0;
      n33 += 1.0 * 1.0;
      r0 += a0 * b;
      r1 += a1 * b;
      r2 += a2 * b;
      r3 += 1.0 * b;
    }
  }
  const cv::Matx44d normal(n00, n01, n02, n03, n01, n11, n12, n13, n02, n12, n22, n23, n03, n13, n23, n33);
  const cv::Vec4d right(r0, r1, r2, r3);
  cv::Vec4d solution;
  if (!cv::solve(normal, right, solution, cv::DECOMP_CHOLESKY))
    throw Error("measure shift: the images hold no texture to register");
  return solution;
}

}  // namespace

Shift2D MeasureShift(const cv::Mat& reference, const cv::Mat& moving, int margin, const cv::Mat& mask) {
  if (reference.type() != CV_32FC1 || moving.type() != CV_32FC1 || reference.size() != moving.size())
    throw Error("measure shift: expected two single-channel float images of one size");
  if (!mask.empty() && (mask.type() != CV_8UC1 || mask.size() != reference.size()))
    throw Error("measure shift: the mask must be an 8-bit single-channel image of the images' size");
  if (margin < 1 || 2 * margin + 2 >= std::min(reference.rows, reference.cols))
    throw Error("measure shift: the margin leaves no pixels");
  // The fitted shift comes scaled by the gain (moving ~ gain (reference - g.d) + offset): divided out, a 0.12 px
  // shift read through a gain of 1.1 comes back as 0.122 (0.134 before).
  const cv::Vec4d solution = LinearisedStep(reference, moving, margin, mask);
  Shift2D shift;
  shift.dx = solution[0] / (1.0 + solution[2]);
  shift.dy = solution[1] / (1.0 + solution[2]);
  return shift;
}

cv::Mat GreyOf(const cv::Mat& rgb) {
  cv::Mat grey;
  cv::transform(rgb, grey, cv::Matx13f(1.0f / 3, 1.0f / 3, 1.0f / 3));
  return grey;
}

cv::Mat LinearGreyOf(const cv::Mat& rgb, Transfer transfer) {
  if (transfer == Transfer::kLinear) return GreyOf(rgb);
  cv::Mat grey(rgb.rows, rgb.cols, CV_32FC1);
  const SrgbTable& table = SrgbToLinearTable();
  for (int y = 0; y < rgb.rows; ++y) {
    const float* in = rgb.ptr<float>(y);
    float* out = grey.ptr<float>(y);
    for (int x = 0; x < rgb.cols; ++x)
      out[x] = (SrgbToLinearTabulated(in[3 * x], table) + SrgbToLinearTabulated(in[3 * x + 1], table) +
                SrgbToLinearTabulated(in[3 * x + 2], table)) /
               3.0f;
  }
  return grey;
}

ViewRegistration RegisterViews(const LightField& decoded, const LightField& truth, double min_weight, int margin,
                               const cv::Mat& mask) {
  if (decoded.shape() != truth.shape())
    throw Error("register views: the light fields differ in shape (" + ToString(decoded.shape()) + " and " +
                ToString(truth.shape()) + ")");
  ViewRegistration result;
  result.views.resize(truth.shape().Views());
  RegisterBlock(decoded, truth, ViewIndex{0, 0}, min_weight, margin, mask, result);
  CountRegistered(result);
  return result;
}

void RegisterBlock(const LightField& decoded, const LightField& truth_views, ViewIndex first, double min_weight,
                   int margin, const cv::Mat& mask, ViewRegistration& result) {
  const LightFieldShape& shape = decoded.shape();
  const LightFieldShape& block = truth_views.shape();
  if (block.width != shape.width || block.height != shape.height || block.channels != shape.channels || first.u < 0 ||
      first.v < 0 || first.u + block.nu > shape.nu || first.v + block.nv > shape.nv)
    throw Error("register views: the ideal light field's " + ToString(block) + " from view (" +
                std::to_string(first.u) + ", " + std::to_string(first.v) + ") do not lie inside the decoded " +
                ToString(shape));
  if (result.views.size() != shape.Views()) throw Error("register views: the result is not sized to every view");
  // Views in parallel (each is independent); the exception of the first view that failed is rethrown as it was.
  ParallelFor(static_cast<int>(block.Views()), [&](int index) {
    const ViewIndex in_block = ViewFromCameraNumber(index, block.nu);
    const ViewIndex view{first.u + in_block.u, first.v + in_block.v};
    ViewShift& entry = result.views[static_cast<std::size_t>(CameraNumber(view, shape.nu))];
    entry.view = view;
    entry.weight = MeanViewWeight(truth_views, in_block);
    if (entry.weight <= min_weight) return;
    entry.shift = MeasureShift(LinearGreyOf(truth_views.View(in_block), truth_views.transfer),
                               LinearGreyOf(decoded.View(view), decoded.transfer), margin, mask);
    entry.registered = true;
  });
}

void CountRegistered(ViewRegistration& registration) {
  registration.registered = 0;
  registration.worst = 0.0;
  for (const ViewShift& entry : registration.views) {
    if (!entry.registered) continue;
    ++registration.registered;
    registration.worst = std::max({registration.worst, std::abs(entry.shift.dx), std::abs(entry.shift.dy)});
  }
}

}  // namespace lfsp
