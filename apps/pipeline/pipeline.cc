#include "pipeline.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>

#include "../input_loading.h"
#include "../report/html_report.h"
#include "../summary.h"
#include "../view_selection.h"
#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/visualize.h"
#include "lfsp/decode/capture_decoder.h"
#include "lfsp/decode/container_info.h"
#include "lfsp/depth/metrics.h"
#include "lfsp/edit/recolor.h"
#include "lfsp/edit/refocus.h"
#include "lfsp/edit/selection.h"
#include "lfsp/segment/evaluate.h"
#include "lfsp/segment/lfsp.h"
#include "lfsp/segment/metrics.h"
#include "pipeline_report.h"
#include "recolor_spec.h"
#include "truth_comparison.h"

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

// The output folder is marked as a pipeline run so a later run may replace its files, while a user's unrelated
// non-empty folder is never written into.
constexpr const char* kRunMarker = ".lfsp-pipeline";

// The run is built in a temporary folder beside `out` and replaces it as a whole when complete, so `out` always
// holds one consistent set (the previous run's or this one's). `out` may be absent, empty, or a previous run.
void CheckOutputFolder(const fs::path& out) {
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec)) ThrowFileError(out.string(), "exists and is not a folder");
  if (fs::exists(out, ec) && !fs::is_empty(out, ec) && !fs::exists(out / kRunMarker, ec))
    ThrowFileError(out.string(), "exists, is not empty and holds no previous pipeline run; refusing to replace it");
}

void MarkRunFolder(const fs::path& work) {
  std::error_code ec;
  fs::create_directories(work, ec);
  if (ec) ThrowFileError(work.string(), "cannot create output folder: " + ec.message());
  std::ofstream marker(work / kRunMarker);
  if (!marker) ThrowFileError(work.string(), "cannot write into the output folder");
}

// Ground truth of a simulated capture, written by `lfsp simulate` beside it (ground_truth/decoded.h5), if its
// shape matches the decoded light field: its disparity and labels go into the bundle, and the decode is compared
// with its ideal light field while that is loaded.
std::optional<TruthComparison> AttachSimulatorGroundTruth(const fs::path& capture, Bundle& decoded) {
  const fs::path truth_path = capture.parent_path() / "ground_truth" / "decoded.h5";
  std::error_code ec;
  if (!fs::exists(truth_path, ec)) return std::nullopt;
  Bundle truth = ReadBundle(truth_path);
  const LightFieldShape& shape = decoded.light_field.shape();
  const LightFieldShape& truth_shape = truth.light_field.shape();
  if (truth_shape.nu != shape.nu || truth_shape.nv != shape.nv || truth_shape.width != shape.width ||
      truth_shape.height != shape.height) {
    spdlog::warn("{}: ground truth is {} but the decoded light field is {}; metrics skipped", truth_path.string(),
                 ToString(truth_shape), ToString(shape));
    return std::nullopt;
  }
  decoded.disparity = std::move(truth.disparity);
  decoded.labels = std::move(truth.labels);
  spdlog::info("ground truth: {}", truth_path.string());
  TruthComparison comparison = CompareWithTruth(decoded.light_field, truth.light_field);
  spdlog::info(
      "decoded against the ideal light field: {} views registered (mean weight > {}), worst shift {:.3f} px; "
      "centre view PSNR {:.2f} dB",
      comparison.registration.registered, TruthComparison::kRegisteredWeight, comparison.registration.worst,
      comparison.centre_psnr_db);
  return comparison;
}

// Depth needs a disparity range: the user's, else the light field's metadata, else the ground truth's (padded),
// else depth estimates it from the views.
depth::DepthOptions WithDisparityRange(depth::DepthOptions options, const Bundle& bundle) {
  if (options.range || DisparityRangeFromMetadata(bundle.light_field.metadata)) return options;
  if (bundle.disparity) {
    DisparityRange range{std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
    for (int i = 0; i < bundle.disparity->width() * bundle.disparity->height(); ++i) {
      const float d = bundle.disparity->data()[i];
      if (!std::isfinite(d)) continue;
      range.min = std::min(range.min, d);
      range.max = std::max(range.max, d);
    }
    const float pad = 0.1f * (range.max - range.min) + 0.05f;
    options.range = DisparityRange{range.min - pad, range.max + pad};
    spdlog::info("disparity range {:.2f} .. {:.2f} from the ground truth", options.range->min, options.range->max);
    return options;
  }
  return options;  // depth estimates it from the views
}

// Bytes of every file the run wrote (relative paths), and their total.
nlohmann::ordered_json OutputSizes(const fs::path& folder) {
  nlohmann::ordered_json sizes = nlohmann::ordered_json::object();
  std::uintmax_t total = 0;
  std::vector<std::pair<std::string, std::uintmax_t>> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.is_regular_file())
      files.emplace_back(fs::relative(entry.path(), folder).generic_string(), entry.file_size());
  std::sort(files.begin(), files.end());
  for (const auto& [name, bytes] : files) {
    sizes[name] = bytes;
    total += bytes;
  }
  sizes["total"] = total;
  return sizes;
}

}  // namespace

fs::path DefaultSample() {
  const char* configured = std::getenv("LFSP_SAMPLES_DIR");
  const fs::path samples = configured ? fs::path(configured) : fs::path(LFSP_SOURCE_SAMPLES_DIR);
  for (const char* candidate : {"mini-illum/capture.LFR", "ideal/ideal.h5"}) {
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
  CheckOutputFolder(options.out);
  AtomicOutput run(options.out);  // also removes what a killed run left beside it
  const fs::path work = run.temporary();
  MarkRunFolder(work);

  PipelineResult result;
  nlohmann::ordered_json& summary = result.summary;
  summary["input"] = input.string();
  summary["output"] = options.out.string();
  nlohmann::ordered_json timings = nlohmann::ordered_json::object();
  StageRunner stages(recolor ? 7 : 6, timings);

  // A .png/.tif is a light field (ESLF) unless a camera says it is a raw Bayer mosaic.
  const bool raw_capture =
      decode::LooksLikeLytroFile(input) || (!options.plain.camera.empty() && decode::IsPlainRawImagePath(input));
  std::optional<TruthComparison> truth_comparison;
  Bundle bundle = stages.Run(raw_capture ? "decode" : "load", [&] {
    Bundle out;
    if (raw_capture) {
      decode::CaptureDecodeOptions decode_options;
      decode_options.white_images = options.white_images;
      decode_options.no_white_image = options.no_white_image;
      decode_options.plain = options.plain;
      decode::CaptureDecodeResult decoded = decode::DecodeCaptureFile(input, decode_options);
      out.light_field = std::move(decoded.light_field);
      summary["decode"] = decoded.summary;
      truth_comparison = AttachSimulatorGroundTruth(input, out);
    } else {
      out = cli::LoadInput(input);
    }
    // The light field is stored once, in segmentation.h5, after the views to process are chosen.
    summary["views"] = cli::SelectViews(out, options.views, input.string());
    return out;
  });
  const LightField& light_field = bundle.light_field;
  summary["light_field"] = ToString(light_field.shape());
  // What depends on the view size is checked before depth, the first long stage.
  segment::RequireSuperpixelSizeFits(options.segment.size, light_field.shape(), "--size");
  if (recolor) edit::RequirePointsInside(recolor->points, light_field.shape().width, light_field.shape().height);

  const depth::DepthResult depth_result = stages.Run("depth", [&] {
    depth::DepthResult estimate = depth::EstimateDepth(light_field, WithDisparityRange(options.depth, bundle));
    WritePfm(estimate.disparity, work / "disparity.pfm");
    WritePfm(estimate.confidence, work / "confidence.pfm");
    return estimate;
  });
  // A range the pipeline took from the ground truth reaches depth as an option: say where it came from.
  const bool from_truth = !options.depth.range && depth_result.range_source == "options";
  summary["disparity_range"] = {{"min", depth_result.range.min},
                                {"max", depth_result.range.max},
                                {"source", from_truth ? "ground truth" : depth_result.range_source}};
  summary["depth_choices"] = {{"noise_sigma", depth_result.noise_sigma},
                              {"presmooth_sigma", depth_result.presmooth_sigma},
                              {"excluded_ring", depth_result.excluded_ring},
                              {"detail_weight", depth_result.detail_weight}};

  const segment::LfspResult segmentation = stages.Run("segment", [&] {
    segment::LfspResult lfsp = segment::SegmentLightField(light_field, depth_result.disparity, options.segment);
    // The bundle is self-contained for `lfsp evaluate segmentation`. The light field and labels are moved in and
    // back out rather than copied: each is a full 4D array.
    Bundle labelled;
    labelled.light_field = std::move(bundle.light_field);
    labelled.disparity = depth_result.disparity;
    labelled.labels = std::move(lfsp.labels);
    // As `lfsp segment` writes it: the parameters travel with the labels (evaluate re-runs the refocus sweep).
    labelled.light_field.metadata["lfsp_segment"] = segment::SegmentationRecord(options.segment, "lfsp depth");
    WriteBundle(labelled, work / "segmentation.h5", CompactBundleOptions(labelled.light_field));
    bundle.light_field = std::move(labelled.light_field);
    lfsp.labels = std::move(*labelled.labels);
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
      SaveLightField(recoloured, work / "recolored.h5");
      const ViewIndex centre = light_field.shape().Centre();
      recolor_figures.before = DisplayRgb8(light_field.View(centre), light_field.transfer);
      recolor_figures.after = DisplayRgb8(recoloured.light_field.View(centre), light_field.transfer);
      WriteImage(recolor_figures.before, work / "recolor_before.png");
      WriteImage(recolor_figures.after, work / "recolor_after.png");
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
    fs::create_directories(work / "focal_stack");
    for (std::size_t i = 0; i < slices.size(); ++i) {
      focal_stack.slices.push_back(DisplayRgb8(slices[i], light_field.transfer));
      char name[64];
      std::snprintf(name, sizeof name, "slice_%02zu_d%+.2f.png", i, focal_stack.disparities[i]);
      WriteImage(focal_stack.slices.back(), work / "focal_stack" / name);
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
    if (truth_comparison) metrics["decode_vs_truth"] = ToJson(*truth_comparison);
    metrics["segmentation"] = segment::ScoreLabels(segmentation.labels, bundle.labels ? &*bundle.labels : nullptr,
                                                   bundle.disparity ? &*bundle.disparity : nullptr,
                                                   bundle.disparity ? &gt_view_disparity : nullptr, 2);
    return 0;
  });

  stages.Run("report", [&] {
    ReportInputs inputs{light_field,
                        depth_result,
                        segmentation,
                        bundle.disparity ? &*bundle.disparity : nullptr,
                        recolor ? &recolor_figures : nullptr,
                        &focal_stack,
                        truth_comparison ? &*truth_comparison : nullptr};
    report::Report report = BuildReport(inputs, options);
    report.metrics = metrics;
    report.timings = timings;  // stages so far; the report stage itself is in summary.json
    std::ofstream file(work / "report.html");
    file << report::RenderHtml(report);
    if (!file.flush()) ThrowFileError((options.out / "report.html").string(), "write failed");
    return 0;
  });

  summary["parameters"] = {{"segment", segment::ToJson(options.segment)},
                           {"depth_labels", options.depth.labels},
                           {"focal_stack_slices", options.focal_stack_slices}};
  summary["metrics"] = metrics;
  summary["output_bytes"] = OutputSizes(work);
  summary["timings"] = timings;
  summary["wall_seconds"] = std::chrono::duration<double>(Clock::now() - wall_start).count();
  cli::WriteJsonSummary(summary, work / "summary.json");
  run.Commit();
  result.report = options.out / "report.html";
  return result;
}

}  // namespace lfsp::pipeline
