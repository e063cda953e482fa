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
  char caption[384];
  std::snprintf(caption, sizeof caption,
                "mean over channels of |gain x decoded - ideal| in linear light (one gain per channel), TURBO over "
                "0 .. %.2f; RMS %.4f, PSNR %.2f dB",
                kErrorPictureTop, comparison.centre_rms, comparison.centre_psnr_db);
  section.figures.push_back({"Centre-view error", caption, CentreErrorPicture(comparison)});
  char away[64] = "";
  if (comparison.depth_edge_margin_px > 0)
    std::snprintf(away, sizeof away, ", %d px or more from the truth's depth edges", comparison.depth_edge_margin_px);
  std::snprintf(caption, sizeof caption,
                "one cell per view (u right, v down): the larger of |dx|, |dy| registering the decoded view on the "
                "ideal one in linear light%s, TURBO over 0 .. %.2f px; black: mean weight <= %.1f. %d views, worst "
                "%.3f px",
                away, kRegistrationPictureTop, TruthComparison::kRegisteredWeight, comparison.registration.registered,
                comparison.registration.worst);
  section.figures.push_back({"Per-view registration", caption, RegistrationPicture(comparison)});
  return section;
}

report::Section SuperpixelSection(const ReportInputs& inputs) {
  const LightField& light_field = inputs.light_field;
  const Labels& labels = inputs.segmentation.labels;
  const LightFieldShape& shape = light_field.shape();
  report::Section section{"Light-field superpixels", {}, {}};
  section.figures.push_back({"LFSP boundaries, centre view",
                             std::to_string(inputs.segmentation.superpixels) + " superpixels",
                             CentreViewBoundaries(light_field, labels)});
  // EPIs through the middle of the view: a consistent segmentation draws boundaries along the EPI lines. The same
  // pictures as segmentation.overlay_epi_h.png and segmentation.overlay_epi_v.png.
  const int y = shape.height / 2;
  const int x = shape.width / 2;
  section.figures.push_back({"Horizontal EPI", "row y = " + std::to_string(y) + " of the middle view row (u down)",
                             HorizontalEpiBoundaries(light_field, labels, y)});
  section.figures.push_back({"Vertical EPI",
                             "column x = " + std::to_string(x) + " of the middle view column (v across)",
                             VerticalEpiBoundaries(light_field, labels, x)});
  return section;
}

// The stage's pictures are display-encoded already: shown as sRGB, they are converted to 8 bits only.
report::Section RecolorSection(const stages::RecolorStageResult& recolor) {
  report::Section section{"Recolouring", {}, {}};
  section.figures.push_back({"Before", "centre view", DisplayRgb8(recolor.before, Transfer::kSrgb)});
  section.figures.push_back(
      {"After", std::to_string(recolor.summary.at("selected_labels").size()) + " superpixels recoloured in every view",
       DisplayRgb8(recolor.after, Transfer::kSrgb)});
  return section;
}

report::Section FocalStackSection(const FocalStackFigures& stack, Transfer transfer) {
  report::Section section{"Focal stack", {}, {}};
  for (std::size_t i = 0; i < stack.slices.size(); ++i) {
    char title[64];
    std::snprintf(title, sizeof title, "Focused at d = %+.2f", stack.disparities[i]);
    section.figures.push_back(
        {title, "shift-and-sum over all views", Thumbnail(DisplayRgb8(stack.slices[i], transfer))});
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
  if (!inputs.focal_stack.slices.empty())
    report.sections.push_back(FocalStackSection(inputs.focal_stack, inputs.light_field.transfer));
  return report;
}

}  // namespace lfsp::pipeline
