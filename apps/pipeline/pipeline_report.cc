#include "pipeline_report.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "lfsp/core/visualize.h"

namespace lfsp::pipeline {
namespace {

constexpr int kMaxFrameWidth = 320;  // keeps the self-contained HTML small

cv::Mat Thumbnail(const cv::Mat& rgb8) {
  if (rgb8.cols <= kMaxFrameWidth) return rgb8;
  cv::Mat small;
  const double scale = static_cast<double>(kMaxFrameWidth) / rgb8.cols;
  cv::resize(rgb8, small, cv::Size(), scale, scale, cv::INTER_AREA);
  return small;
}

// The views along the middle row, then down the middle column: the parallax a person looks for.
std::vector<cv::Mat> ViewSweep(const LightField& light_field) {
  std::vector<cv::Mat> frames = ViewSweepFrames(light_field);
  for (cv::Mat& frame : frames) frame = Thumbnail(frame);
  return frames;
}

cv::Mat GreyToRgb8(const DisparityMap& values) {
  cv::Mat grey;
  values.Mat().convertTo(grey, CV_8U, 255.0);
  cv::Mat rgb;
  cv::cvtColor(grey, rgb, cv::COLOR_GRAY2RGB);
  return rgb;
}

report::Section LightFieldSection(const LightField& light_field) {
  const ViewIndex centre = light_field.shape().Centre();
  report::Section section{"Light field", {}, {}};
  section.figures.push_back({"Centre view", ToString(light_field.shape()) + ", " + ToString(light_field.transfer),
                             DisplayRgb8(light_field.View(centre), light_field.transfer)});
  section.animations.push_back({"Sweep through the views", "middle row left to right, then middle column top to bottom",
                                ViewSweep(light_field), 8});
  return section;
}

report::Section DepthSection(const ReportInputs& inputs) {
  report::Section section{"Depth", {}, {}};
  const DisparityRange range = inputs.depth.range;
  char caption[128];
  std::snprintf(caption, sizeof caption, "centre-view disparity, TURBO colour map over %.2f .. %.2f px/view", range.min,
                range.max);
  section.figures.push_back({"Estimated disparity", caption, ColourMapDisparity(inputs.depth.disparity, range)});
  if (inputs.ground_truth_disparity != nullptr)
    section.figures.push_back(
        {"Ground-truth disparity", "same colour scale", ColourMapDisparity(*inputs.ground_truth_disparity, range)});
  section.figures.push_back({"Confidence", "white = confident", GreyToRgb8(inputs.depth.confidence)});
  return section;
}

report::Section TruthComparisonSection(const TruthComparison& comparison) {
  report::Section section{"Decoded against the ideal light field", {}, {}};
  char caption[256];
  std::snprintf(caption, sizeof caption,
                "mean over channels of |gain x decoded - ideal| in linear light (one gain per channel), TURBO over "
                "0 .. %.2f; RMS %.4f, PSNR %.2f dB",
                kErrorPictureTop, comparison.centre_rms, comparison.centre_psnr_db);
  section.figures.push_back({"Centre-view error", caption, CentreErrorPicture(comparison)});
  std::snprintf(caption, sizeof caption,
                "one cell per view (u right, v down): the larger of |dx|, |dy| registering the decoded view on the "
                "ideal one, TURBO over 0 .. %.2f px; black: mean weight <= %.1f. %d views, worst %.3f px",
                kRegistrationPictureTop, TruthComparison::kRegisteredWeight, comparison.registration.registered,
                comparison.registration.worst);
  section.figures.push_back({"Per-view registration", caption, RegistrationPicture(comparison)});
  return section;
}

report::Section SuperpixelSection(const ReportInputs& inputs) {
  const LightField& light_field = inputs.light_field;
  const Labels& labels = inputs.segmentation.labels;
  const LightFieldShape& shape = light_field.shape();
  const ViewIndex centre = shape.Centre();
  report::Section section{"Light-field superpixels", {}, {}};
  const cv::Mat centre_rgb = DisplayRgb8(light_field.View(centre), light_field.transfer);
  section.figures.push_back({"LFSP boundaries, centre view",
                             std::to_string(inputs.segmentation.superpixels) + " superpixels",
                             DrawLabelBoundaries(centre_rgb, labels.View(centre))});

  // EPIs through the middle of the view: a consistent segmentation draws boundaries along the EPI lines.
  const int stretch = std::max(4, 96 / std::max(shape.nu, shape.nv));
  const int y = shape.height / 2;
  const int x = shape.width / 2;
  const cv::Mat horizontal = DrawLabelBoundaries(
      DisplayRgb8(HorizontalEpi(light_field, y, centre.v), light_field.transfer), HorizontalEpi(labels, y, centre.v));
  const cv::Mat vertical = DrawLabelBoundaries(DisplayRgb8(VerticalEpi(light_field, x, centre.u), light_field.transfer),
                                               VerticalEpi(labels, x, centre.u));
  section.figures.push_back({"Horizontal EPI", "row y = " + std::to_string(y) + " of the middle view row (u down)",
                             Enlarge(horizontal, 1, stretch)});
  section.figures.push_back({"Vertical EPI",
                             "column x = " + std::to_string(x) + " of the middle view column (v across)",
                             Enlarge(vertical, stretch, 1)});
  return section;
}

report::Section RecolorSection(const RecolorFigures& recolor) {
  report::Section section{"Recolouring", {}, {}};
  section.figures.push_back({"Before", "centre view", recolor.before});
  section.figures.push_back(
      {"After", std::to_string(recolor.selected_labels) + " superpixels recoloured in every view", recolor.after});
  return section;
}

report::Section FocalStackSection(const FocalStackFigures& stack) {
  report::Section section{"Focal stack", {}, {}};
  for (std::size_t i = 0; i < stack.slices.size(); ++i) {
    char title[64];
    std::snprintf(title, sizeof title, "Focused at d = %+.2f", stack.disparities[i]);
    section.figures.push_back({title, "shift-and-sum over all views", Thumbnail(stack.slices[i])});
  }
  return section;
}

}  // namespace

report::Report BuildReport(const ReportInputs& inputs, const PipelineOptions& options) {
  report::Report report;
  report.title = "lfsp pipeline report";
  report.subtitle =
      (options.input.empty() ? std::string("bundled sample") : options.input.string()) + " -> " + options.out.string();
  report.sections.push_back(LightFieldSection(inputs.light_field));
  if (inputs.truth_comparison != nullptr) report.sections.push_back(TruthComparisonSection(*inputs.truth_comparison));
  report.sections.push_back(DepthSection(inputs));
  report.sections.push_back(SuperpixelSection(inputs));
  if (inputs.recolor != nullptr) report.sections.push_back(RecolorSection(*inputs.recolor));
  if (inputs.focal_stack != nullptr) report.sections.push_back(FocalStackSection(*inputs.focal_stack));
  return report;
}

}  // namespace lfsp::pipeline
