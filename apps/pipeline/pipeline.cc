#include "pipeline.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdlib>
#include <fstream>

#include "../report/html_report.h"
#include "../summary.h"
#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/visualize.h"
#include "lfsp/depth/metrics.h"
#include "lfsp/edit/recolor.h"
#include "lfsp/edit/refocus.h"
#include "lfsp/edit/selection.h"
#include "lfsp/segment/lfsp.h"
#include "lfsp/segment/metrics.h"
#include "pipeline_report.h"
#include "recolor_spec.h"

namespace lfsp::pipeline {
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

// Runs the stages in order, logging "[i/n] name" and recording each stage's wall time.
class StageRunner {
 public:
  StageRunner(int stage_count, nlohmann::ordered_json& timings) : count_(stage_count), timings_(timings) {}

  template <typename Work>
  auto Run(const std::string& name, Work work) {
    ++index_;
    spdlog::info("[{}/{}] {}", index_, count_, name);
    const auto start = Clock::now();
    struct Record {
      StageRunner* runner;
      std::string name;
      Clock::time_point start;
      ~Record() { runner->timings_[name] = std::chrono::duration<double>(Clock::now() - start).count(); }
    } record{this, name, start};
    return work();
  }

 private:
  int count_;
  int index_ = 0;
  nlohmann::ordered_json& timings_;
};

void PrepareOutputFolder(const fs::path& out) {
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec)) ThrowFileError(out.string(), "exists and is not a folder");
  if (fs::exists(out, ec) && !fs::is_empty(out, ec) && !fs::exists(out / "summary.json", ec))
    ThrowFileError(out.string(), "exists, is not empty and holds no previous pipeline run; refusing to write into it");
  fs::create_directories(out, ec);
  if (ec) ThrowFileError(out.string(), "cannot create output folder: " + ec.message());
}

nlohmann::ordered_json SegmentationMetrics(const Bundle& input, const segment::LfspResult& result,
                                           const std::vector<DisparityMap>* gt_view_disparity) {
  nlohmann::ordered_json metrics;
  metrics["superpixels"] = result.superpixels;
  metrics["effective_label_ratio"] = segment::EffectiveLabelRatio(result.labels);
  if (gt_view_disparity != nullptr) {
    metrics["self_similarity_px"] = segment::SelfSimilarity(result.labels, *gt_view_disparity);
    metrics["labels_per_pixel"] = segment::LabelsPerPixel(result.labels, *input.disparity, *gt_view_disparity);
  }
  if (input.labels) {
    metrics["boundary_recall"] = segment::BoundaryRecall(result.labels, *input.labels);
    metrics["undersegmentation_error"] = segment::UndersegmentationError(result.labels, *input.labels);
    metrics["achievable_segmentation_accuracy"] = segment::AchievableSegmentationAccuracy(result.labels, *input.labels);
  }
  metrics["compactness"] = segment::Compactness(result.labels);
  return metrics;
}

}  // namespace

fs::path DefaultSample() {
  const char* configured = std::getenv("LFSP_SAMPLES_DIR");
  const fs::path samples = configured ? fs::path(configured) : fs::path(LFSP_SOURCE_SAMPLES_DIR);
  for (const char* candidate : {"mini-illum/ideal.h5", "ideal/light_field.h5"}) {
    std::error_code ec;
    if (fs::exists(samples / candidate, ec)) return samples / candidate;
  }
  throw Error(samples.string() + ": no bundled sample found (regenerate with tools/make_samples, or pass an INPUT)");
}

PipelineResult RunPipeline(const PipelineOptions& options) {
  const auto wall_start = Clock::now();
  const fs::path input = options.input.empty() ? DefaultSample() : options.input;
  // Parse everything the user typed before any work, so a typo fails at once.
  const std::optional<RecolorSpec> recolor =
      options.recolor.empty() ? std::nullopt : std::optional<RecolorSpec>(ParseRecolorSpec(options.recolor));
  PrepareOutputFolder(options.out);

  PipelineResult result;
  nlohmann::ordered_json& summary = result.summary;
  summary["input"] = input.string();
  summary["output"] = options.out.string();
  nlohmann::ordered_json timings = nlohmann::ordered_json::object();
  StageRunner stages(recolor ? 7 : 6, timings);

  Bundle bundle = stages.Run("load", [&] { return LoadLightField(input); });
  const LightField& light_field = bundle.light_field;
  summary["light_field"] = ToString(light_field.shape());

  const depth::DepthResult depth_result = stages.Run("depth", [&] {
    depth::DepthResult estimate = depth::EstimateDepth(light_field, options.depth);
    WritePfm(estimate.disparity, options.out / "disparity.pfm");
    WritePfm(estimate.confidence, options.out / "confidence.pfm");
    return estimate;
  });
  summary["disparity_range"] = {{"min", depth_result.range.min}, {"max", depth_result.range.max}};

  const segment::LfspResult segmentation = stages.Run("segment", [&] {
    segment::LfspResult lfsp = segment::SegmentLightField(light_field, depth_result.disparity, options.segment);
    Bundle labelled;
    labelled.light_field = light_field;  // the bundle is self-contained for `lfsp evaluate segmentation`
    labelled.disparity = depth_result.disparity;
    labelled.labels = lfsp.labels;
    WriteBundle(labelled, options.out / "segmentation.h5");
    return lfsp;
  });

  RecolorFigures recolor_figures;
  if (recolor) {
    stages.Run("recolor", [&] {
      const Labels& labels = segmentation.labels;
      const std::vector<std::int32_t> selection = recolor->points.empty()
                                                      ? edit::SelectLabelIds(labels, recolor->ids)
                                                      : edit::SelectAtPoints(labels, recolor->points);
      Bundle recoloured;
      recoloured.light_field = light_field;
      const edit::RecolorStats stats = edit::Recolor(recoloured.light_field, labels, selection, recolor->options);
      SaveLightField(recoloured, options.out / "recolored.h5");
      const ViewIndex centre = light_field.shape().Centre();
      recolor_figures.before = DisplayRgb8(light_field.View(centre), light_field.transfer);
      recolor_figures.after = DisplayRgb8(recoloured.light_field.View(centre), light_field.transfer);
      WriteImage(recolor_figures.before, options.out / "recolor_before.png");
      WriteImage(recolor_figures.after, options.out / "recolor_after.png");
      recolor_figures.selected_labels = selection.size();
      summary["recolor"] = {{"spec", options.recolor},
                            {"selected_labels", selection.size()},
                            {"selected_rays", stats.selected_rays},
                            {"changed_rays", stats.changed_rays}};
      return 0;
    });
  }

  FocalStackFigures focal_stack;
  stages.Run("refocus", [&] {
    focal_stack.disparities =
        edit::EvenlySpacedDisparities(depth_result.range.min, depth_result.range.max, options.focal_stack_slices);
    const std::vector<cv::Mat> slices = edit::FocalStack(light_field, focal_stack.disparities);
    fs::create_directories(options.out / "focal_stack");
    for (std::size_t i = 0; i < slices.size(); ++i) {
      focal_stack.slices.push_back(DisplayRgb8(slices[i], light_field.transfer));
      char name[64];
      std::snprintf(name, sizeof name, "slice_%02zu_d%+.2f.png", i, focal_stack.disparities[i]);
      WriteImage(focal_stack.slices.back(), options.out / "focal_stack" / name);
    }
    return 0;
  });

  nlohmann::ordered_json metrics = nlohmann::ordered_json::object();
  stages.Run("evaluate", [&] {
    std::vector<DisparityMap> gt_view_disparity;
    if (bundle.disparity) {
      metrics["depth"] = depth::ToJson(depth::EvaluateDisparity(depth_result.disparity, *bundle.disparity));
      gt_view_disparity = segment::PropagateDisparity(*bundle.disparity, light_field.shape());
    }
    metrics["segmentation"] =
        SegmentationMetrics(bundle, segmentation, bundle.disparity ? &gt_view_disparity : nullptr);
    return 0;
  });

  stages.Run("report", [&] {
    ReportInputs inputs{light_field,
                        depth_result,
                        segmentation,
                        bundle.disparity ? &*bundle.disparity : nullptr,
                        recolor ? &recolor_figures : nullptr,
                        &focal_stack};
    report::Report report = BuildReport(inputs, options);
    report.metrics = metrics;
    report.timings = timings;  // stages so far; the report stage itself is in summary.json
    AtomicOutput html(options.out / "report.html");
    {
      std::ofstream file(html.temporary());
      file << report::RenderHtml(report);
      if (!file.flush()) ThrowFileError((options.out / "report.html").string(), "write failed");
    }
    html.Commit();
    return 0;
  });

  summary["parameters"] = {{"segment", segment::ToJson(options.segment)},
                           {"depth_labels", options.depth.labels},
                           {"focal_stack_slices", options.focal_stack_slices}};
  summary["metrics"] = metrics;
  summary["timings"] = timings;
  summary["wall_seconds"] = std::chrono::duration<double>(Clock::now() - wall_start).count();
  cli::WriteJsonSummary(summary, options.out / "summary.json");
  result.report = options.out / "report.html";
  return result;
}

}  // namespace lfsp::pipeline
