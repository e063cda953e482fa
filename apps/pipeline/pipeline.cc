#include "pipeline.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>

#include "input_loading.h"
#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/memory_usage.h"
#include "lfsp/core/stats.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/core/view_crop.h"
#include "lfsp/decode/container_info.h"
#include "lfsp/depth/depth_io.h"
#include "lfsp/edit/refocus.h"
#include "lfsp/edit/selection.h"
#include "lfsp/segment/lfsp.h"
#include "pipeline_report.h"
#include "recolor_spec.h"
#include "report/html_report.h"
#include "stages/decode_stage.h"
#include "stages/depth_stage.h"
#include "stages/evaluate_stage.h"
#include "stages/recolor_stage.h"
#include "stages/refocus_stage.h"
#include "stages/segment_stage.h"
#include "stages/summary.h"
#include "truth_comparison.h"
#include "view_selection.h"

namespace lfsp::pipeline {
namespace fs = std::filesystem;

namespace {

// Runs the stages in order, logging "[i/n] name" and recording each stage's wall time, and the process's resident
// and peak memory at its end (MB) into `memory`.
class StageRunner {
 public:
  StageRunner(int stage_count, nlohmann::ordered_json& timings, nlohmann::ordered_json& memory)
      : count_(stage_count), timings_(timings), memory_(memory) {}

  template <typename Work>
  auto Run(const std::string& name, Work work) {
    ++index_;
    spdlog::info("[{}/{}] {}", index_, count_, name);
    struct Record {  // records the time even when the stage throws
      StageRunner* runner;
      std::string name;
      Stopwatch stopwatch;
      ~Record() {
        // What the stage freed goes back before the next one: in the executable's heap (lfsp_main.cc) its blocks
        // would otherwise stay resident wherever the next stage's buffers do not fit into them, and the resident
        // memory would creep up stage by stage (a full Illum run: 1101 MB after depth, 1208 after the report).
        ReturnFreedMemory();
        runner->timings_[name] = stopwatch.Seconds();
        runner->memory_[name] = {{"resident_mb", ResidentMegabytes()}, {"peak_resident_mb", PeakResidentMegabytes()}};
      }
    } record{this, name, {}};
    return work();
  }

 private:
  int count_;
  int index_ = 0;
  nlohmann::ordered_json& timings_;
  nlohmann::ordered_json& memory_;
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

// The ground truth of a simulated capture, written by `lfsp simulate` beside it (ground_truth/decoded.h5), if its
// shape matches the decoded light field's, or holds it as its central views.
std::optional<fs::path> SimulatorGroundTruth(const fs::path& capture, const LightFieldShape& shape) {
  const fs::path truth_path = capture.parent_path() / "ground_truth" / "decoded.h5";
  std::error_code ec;
  if (!fs::exists(truth_path, ec)) return std::nullopt;
  const LightFieldShape truth_shape = ReadBundleShape(truth_path);
  // The decode holds only the central views of the simulator's grid when the pipeline kept fewer (CompareWithTruth
  // reads the truth's central block).
  const bool central_block = truth_shape.nu == truth_shape.nv && shape.nu == shape.nv && truth_shape.nu > shape.nu &&
                             (truth_shape.nu - shape.nu) % 2 == 0;
  if ((!central_block && (truth_shape.nu != shape.nu || truth_shape.nv != shape.nv)) ||
      truth_shape.width != shape.width || truth_shape.height != shape.height) {
    spdlog::warn("{}: ground truth is {} but the decoded light field is {}; metrics skipped", truth_path.string(),
                 ToString(truth_shape), ToString(shape));
    return std::nullopt;
  }
  spdlog::info("ground truth: {}", truth_path.string());
  return truth_path;
}

// The truth's disparity goes into the bundle, and the decode is compared with its ideal light field, read from the
// file a row of views at a time. (Its labels are read by the evaluation: TruthLabelsOfKeptViews.)
TruthComparison AttachTruthDisparityAndCompare(const fs::path& truth, Bundle& decoded) {
  BundleParts disparity_only;
  disparity_only.samples = false;
  disparity_only.labels = false;
  decoded.disparity = ReadBundle(truth, disparity_only).disparity;
  TruthComparison comparison = CompareWithTruth(decoded.light_field, truth, decoded.disparity);
  spdlog::info(
      "decoded against the ideal light field: {} views registered (mean weight > {}), worst shift {:.3f} px; "
      "centre view PSNR {:.2f} dB",
      comparison.registration.registered, TruthComparison::kRegisteredWeight, comparison.registration.worst,
      comparison.centre_psnr_db);
  return comparison;
}

// The truth's labels of the views the run keeps (the central n x n of the truth's views, n the kept light field's
// view count), if it has labels: what cropping all of them would give, without the rest in memory.
std::optional<Labels> TruthLabelsOfKeptViews(const fs::path& truth, const LightFieldShape& kept) {
  BundleParts labels_only;
  labels_only.views = CentralViewBlock(ReadBundleShape(truth), kept.nu);
  labels_only.samples = false;
  labels_only.disparity = false;
  return ReadBundle(truth, labels_only).labels;
}

// Depth needs a disparity range: the user's, else the light field's metadata, else the ground truth's (padded),
// else depth estimates it from the views.
depth::DepthOptions WithDisparityRange(depth::DepthOptions options, const Bundle& bundle) {
  if (options.range || DisparityRangeFromMetadata(bundle.light_field.metadata) || !bundle.disparity) return options;
  const ValueStats truth = DisparityStats(*bundle.disparity);
  if (truth.count == 0) return options;
  const float pad = static_cast<float>(0.1 * (truth.max - truth.min) + 0.05);
  options.range = DisparityRange{static_cast<float>(truth.min) - pad, static_cast<float>(truth.max) + pad};
  spdlog::info("disparity range {:.2f} .. {:.2f} from the ground truth", options.range->min, options.range->max);
  return options;
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

// A .png/.tif is a light field (ESLF) unless a camera says it is a raw Bayer mosaic.
bool IsRawCapture(const fs::path& input, const PipelineOptions& options) {
  return decode::LooksLikeLytroFile(input) || (!options.plain.camera.empty() && decode::IsPlainRawImagePath(input));
}

// The light field to process, its samples as segmentation.h5 will store them (so every later stage computes what the
// single commands compute from the written files), the views chosen, and a simulated capture's ground truth: its
// disparity in the bundle, its comparison with the decode, and its path (the evaluation reads its labels).
Bundle LoadOrDecode(const fs::path& input, const PipelineOptions& options, nlohmann::ordered_json& summary,
                    std::optional<TruthComparison>& truth_comparison, std::optional<fs::path>& truth) {
  Bundle bundle;
  Stopwatch step;
  const bool raw = IsRawCapture(input, options);
  nlohmann::ordered_json steps;  // the stage's steps' seconds, into summary["step_seconds"]["decode" or "load"]
  if (raw) {
    decode::CaptureDecodeOptions decode_options;
    decode_options.white_images = options.white_images;
    decode_options.no_white_image = options.no_white_image;
    decode_options.grid = options.grid;
    decode_options.plain = options.plain;
    // Only the views the stages will keep are decoded (by default a margin wider than the well-lit ones, which
    // SelectViews below then chooses exactly): the rest would be sliced, stored and compared for nothing.
    decode_options.decode.central_views = options.views;
    stages::DecodeStageResult decoded = stages::RunDecodeStage(input, decode_options);
    bundle = std::move(decoded.bundle);
    summary["decode"] = std::move(decoded.summary);
    steps["decode"] = step.Lap();
    // A simulated capture's truth is read and compared here, inside the stage: what it costs is reported apart.
    truth = SimulatorGroundTruth(input, bundle.light_field.shape());
    // The decode's sensor-size buffers are free but kept in the heap (apps/lfsp_main.cc): given back first, or the
    // truth's rows are read beside them and the peak rises above the decode's (2107 against 1986 MB when all 15x15
    // Illum views were decoded).
    if (truth) ReturnFreedMemory();
    if (truth) truth_comparison = AttachTruthDisparityAndCompare(*truth, bundle);
    steps["ground_truth"] = step.Lap();
  } else {
    // Only the views the stages keep are read (an .h5 bundle of 15x15 views is never whole in memory).
    nlohmann::json views;
    bundle = cli::LoadSelectedViews(input, options.views, views);
    summary["views"] = views;
    RoundToStoredPrecision(bundle.light_field, CompactBundleOptions(bundle.light_field).storage);
    steps["load"] = step.Lap();
  }
  // The light field is stored once, in segmentation.h5, after the views to process are chosen.
  if (raw) summary["views"] = cli::SelectViews(bundle, options.views, input.string());
  steps["select_views"] = step.Lap();
  summary["step_seconds"][raw ? "decode" : "load"] = steps;
  summary["light_field"] = ToString(bundle.light_field.shape());
  return bundle;
}

// The depth stage's choices, and where its disparity range came from (a range the pipeline took from the ground
// truth reaches depth as an option).
nlohmann::ordered_json DepthSummary(const stages::DepthStageResult& depth, const PipelineOptions& options) {
  const depth::DepthResult& estimate = depth.estimate;
  const bool from_truth = !options.depth.range && estimate.range_source == "options";
  return {{"disparity_range",
           {{"min", estimate.range.min},
            {"max", estimate.range.max},
            {"source", from_truth ? "ground truth" : estimate.range_source}}},
          {"depth_choices", depth::AutomaticChoicesToJson(estimate)}};
}

// `--recolor`: the recolour stage on a copy of the light field (the report and the focal stack show the original),
// with the labels and disparity, as `lfsp recolor segmentation.h5` would read them.
stages::RecolorStageResult RecolorStage(const RecolorSpec& spec, const Bundle& bundle, const DisparityMap& disparity,
                                        const Labels& labels, const fs::path& work) {
  stages::RecolorStageOptions options;
  options.recolor = spec.options;
  if (spec.points.empty()) {
    options.selection = edit::SelectLabelIds(labels, spec.ids);
    options.how = {{"by", "label-ids"}, {"label_ids", spec.ids}};
  } else {
    options.selection = edit::SelectAtPoints(labels, spec.points);
    nlohmann::ordered_json points = nlohmann::ordered_json::array();
    for (const cv::Point& point : spec.points)
      points.push_back(std::to_string(point.x) + "," + std::to_string(point.y));
    options.how = {{"by", "at"}, {"points", points}};
  }
  Bundle recoloured;
  recoloured.light_field = bundle.light_field;
  recoloured.disparity = disparity;
  recoloured.labels = labels;
  return stages::RunRecolorStage(recoloured, options, work / "recolored.h5", {{"input", "segmentation.h5"}});
}

void WriteReport(const ReportInputs& inputs, const PipelineOptions& options, const nlohmann::ordered_json& metrics,
                 const nlohmann::ordered_json& timings, const fs::path& path) {
  report::Report report = BuildReport(inputs, options);
  report.metrics = metrics;
  report.timings = timings;  // stages so far; the report stage itself is in summary.json
  report.raw_json = "summary.json";
  std::ofstream file(path);
  file << report::RenderHtml(report);
  if (!file.flush()) ThrowFileError((options.out / "report.html").string(), "write failed");
}

// The samples installed with the command (<prefix>/share/lfsp/samples beside <prefix>/bin/lfsp, as `cmake --install`
// and the .deb put them), else the source tree's.
fs::path BundledSamples() {
  std::error_code ec;
  const fs::path command = fs::read_symlink("/proc/self/exe", ec);
  const fs::path installed = command.parent_path().parent_path() / "share" / "lfsp" / "samples";
  if (!ec && fs::is_directory(installed, ec)) return installed;
  return LFSP_SOURCE_SAMPLES_DIR;
}

}  // namespace

fs::path DefaultSample() {
  const char* configured = std::getenv("LFSP_SAMPLES_DIR");
  const fs::path samples = configured ? fs::path(configured) : BundledSamples();
  for (const char* candidate : {"mini-illum/capture.LFR", "ideal/ideal.h5"}) {
    std::error_code ec;
    if (fs::exists(samples / candidate, ec)) return samples / candidate;
  }
  throw Error(samples.string() + ": no bundled sample found (regenerate with tools/make_samples, or pass an INPUT)");
}

PipelineResult RunPipeline(const PipelineOptions& options) {
  const Stopwatch wall;
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
  nlohmann::ordered_json memory = nlohmann::ordered_json::object();
  StageRunner stages(recolor ? 7 : 6, timings, memory);

  std::optional<TruthComparison> truth_comparison;
  std::optional<fs::path> truth;  // a simulated capture's ground truth
  Bundle bundle = stages.Run(IsRawCapture(input, options) ? "decode" : "load",
                             [&] { return LoadOrDecode(input, options, summary, truth_comparison, truth); });
  LightField& light_field = bundle.light_field;
  // What depends on the view size is checked before depth, the first long stage.
  segment::RequireSuperpixelSizeFits(options.segment.size, light_field.shape(), "--size");
  if (recolor) edit::RequirePointsInside(recolor->points, light_field.shape().width, light_field.shape().height);

  // Each stage writes what its command writes; the pipeline keeps their summaries under the stage's name.
  const stages::DepthStageResult depth = stages.Run("depth", [&] {
    return stages::RunDepthStage(bundle, WithDisparityRange(options.depth, bundle), work / "disparity.pfm",
                                 {{"input", input.string()}});
  });
  summary.update(DepthSummary(depth, options));
  const stages::SegmentStageResult segmentation = stages.Run("segment", [&] {
    stages::SegmentStageOptions segment_options;
    segment_options.params = options.segment;
    return stages::RunSegmentStage(light_field, depth.estimate.disparity, (options.out / "disparity.pfm").string(),
                                   segment_options, work / "segmentation.h5", {{"input", input.string()}});
  });

  std::optional<stages::RecolorStageResult> recoloured;
  if (recolor) {
    recoloured = stages.Run("recolor", [&] {
      return RecolorStage(*recolor, bundle, depth.estimate.disparity, segmentation.lfsp.labels, work);
    });
    summary["recolor"] = {{"spec", options.recolor},
                          {"selected_labels", recoloured->summary.at("selected_labels").size()},
                          {"selected_rays", recoloured->stats.selected_rays},
                          {"changed_rays", recoloured->stats.changed_rays}};
  }

  stages::RefocusStageOptions refocus_options;
  refocus_options.disparities =
      edit::EvenlySpacedDisparities(depth.estimate.range.min, depth.estimate.range.max, options.focal_stack_slices);
  const stages::RefocusStageResult focal_stack = stages.Run("refocus", [&] {
    return stages::RunRefocusStage(bundle, refocus_options, work / "focal_stack", {{"input", input.string()}});
  });

  const nlohmann::ordered_json metrics = stages.Run("evaluate", [&] {
    // A simulated capture's truth labels are read only now: held from the decode on, they sat in depth's peak (83 MB
    // for the Illum's 9x9 views, issue 46).
    if (truth) bundle.labels = TruthLabelsOfKeptViews(*truth, light_field.shape());
    nlohmann::ordered_json scores =
        stages::ScoreRun(depth.estimate.disparity, segmentation.lfsp.labels,
                         {bundle.disparity ? &*bundle.disparity : nullptr, bundle.labels ? &*bundle.labels : nullptr});
    if (truth_comparison) scores["decode_vs_truth"] = ToJson(*truth_comparison);
    if (depth.summary.contains("lattice_peak"))
      scores["depth_maps"] = {{"lattice_peak", depth.summary["lattice_peak"]}};
    return scores;
  });

  stages.Run("report", [&] {
    const ReportInputs inputs{light_field,
                              depth.estimate,
                              segmentation.lfsp,
                              bundle.disparity ? &*bundle.disparity : nullptr,
                              recoloured ? &*recoloured : nullptr,
                              FocalStackFigures{refocus_options.disparities, focal_stack.slices},
                              truth_comparison ? &*truth_comparison : nullptr};
    WriteReport(inputs, options, metrics, timings, work / "report.html");
    return 0;
  });

  summary["parameters"] = {{"segment", segment::ToJson(options.segment)},
                           {"depth_labels", options.depth.labels},
                           {"focal_stack_slices", options.focal_stack_slices}};
  summary["metrics"] = metrics;
  summary["output_bytes"] = OutputSizes(work);
  summary["timings"] = timings;
  summary["memory"] = memory;
  summary["wall_seconds"] = wall.Seconds();
  stages::WriteJsonSummary(summary, work / "summary.json");
  run.Commit();
  result.report = options.out / "report.html";
  return result;
}

}  // namespace lfsp::pipeline
