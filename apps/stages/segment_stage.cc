#include "stages/segment_stage.h"

#include <spdlog/spdlog.h>

#include "lfsp/core/error.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/core/visualize.h"
#include "lfsp/segment/metrics.h"
#include "lfsp/segment/output.h"
#include "stages/summary.h"

namespace lfsp::stages {
namespace fs = std::filesystem;

namespace {

fs::path Beside(const fs::path& output, const std::string& suffix) {
  fs::path path = output;
  path.replace_extension();
  return path.string() + suffix;
}

// The bundle is written with the light field moved in and back out, and the labels copied once (they stay in the
// result): a full 4D light field is the one thing never to copy.
void WriteLabelledBundle(LightField& light_field, const DisparityMap& disparity, const Labels& labels,
                         const fs::path& out) {
  Bundle labelled;
  labelled.light_field = std::move(light_field);
  struct MoveBack {  // back to the caller even when writing fails
    LightField& destination;
    Bundle& bundle;
    ~MoveBack() { destination = std::move(bundle.light_field); }
  } move_back{light_field, labelled};
  labelled.disparity = disparity;
  labelled.labels = labels;
  WriteBundle(labelled, out, CompactBundleOptions(labelled.light_field));
}

// The EPI pictures' row and column must lie in the view: checked before the segmentation, not after it.
void RequireEpiLinesInside(const SegmentStageOptions& options, const LightFieldShape& shape) {
  if (options.epi_row >= shape.height)
    throw Error(OptionName("epi_row") + ": row " + std::to_string(options.epi_row) + " is outside the " +
                std::to_string(shape.height) + "-pixel-high views");
  if (options.epi_column >= shape.width)
    throw Error(OptionName("epi_column") + ": column " + std::to_string(options.epi_column) + " is outside the " +
                std::to_string(shape.width) + "-pixel-wide views");
}

// The files this run has written beside OUT, removed again if the stage fails before its last one: the pictures and
// planes of a segmentation whose bundle was never written are no result.
class SideOutputs {
 public:
  ~SideOutputs() {
    std::error_code ec;
    if (!complete_)
      for (const fs::path& path : paths_) fs::remove(path, ec);
  }
  void Written(fs::path path) { paths_.push_back(std::move(path)); }
  void Complete() { complete_ = true; }

 private:
  std::vector<fs::path> paths_;
  bool complete_ = false;
};

}  // namespace

SegmentStageResult RunSegmentStage(LightField& light_field, const DisparityMap& disparity,
                                   const std::string& disparity_source, const SegmentStageOptions& options,
                                   const fs::path& out, nlohmann::ordered_json summary) {
  const Stopwatch stopwatch;
  RequireEpiLinesInside(options, light_field.shape());
  SegmentStageResult result;
  segment::LfspResult& lfsp = result.lfsp = segment::SegmentLightField(light_field, disparity, options.params);
  spdlog::info("{} superpixels, {} label moves in {} iterations ({:.2f} s)", lfsp.superpixels, lfsp.label_moves,
               lfsp.iterations_run, lfsp.timings.total_seconds);

  const LightFieldShape shape = light_field.shape();
  const int row = options.epi_row >= 0 ? options.epi_row : shape.height / 2;
  const int column = options.epi_column >= 0 ? options.epi_column : shape.width / 2;
  const Stopwatch write;  // the overlays, the planes and the bundle
  const fs::path planes_path = Beside(out, ".planes.json");
  const fs::path centre_path = Beside(out, ".overlay_centre.png");
  const fs::path epi_h_path = Beside(out, ".overlay_epi_h.png");
  const fs::path epi_v_path = Beside(out, ".overlay_epi_v.png");
  SideOutputs side_outputs;
  WriteImage(CentreViewBoundaries(light_field, lfsp.labels), centre_path);
  side_outputs.Written(centre_path);
  WriteImage(HorizontalEpiBoundaries(light_field, lfsp.labels, row), epi_h_path);
  side_outputs.Written(epi_h_path);
  WriteImage(VerticalEpiBoundaries(light_field, lfsp.labels, column), epi_v_path);
  side_outputs.Written(epi_v_path);
  WriteJsonSummary(segment::PlanesToJson(lfsp.planes), planes_path);
  side_outputs.Written(planes_path);
  if (!options.labels_png.empty()) segment::WriteLabelPngs(lfsp.labels, options.labels_png);
  // The parameters travel with the labels: `lfsp evaluate segmentation` re-runs its refocus sweep with them.
  light_field.metadata["lfsp_segment"] = segment::SegmentationRecord(options.params, disparity_source);
  WriteLabelledBundle(light_field, disparity, lfsp.labels, out);
  const double write_seconds = write.Seconds();

  summary["disparity"] = disparity_source;
  summary["shape"] = ToString(shape);
  // Outputs by name: they lie beside the summary, wherever the folder is moved (a pipeline run is built elsewhere).
  summary["outputs"] = {{"bundle", out.filename().string()},
                        {"planes", planes_path.filename().string()},
                        {"overlay_centre", centre_path.filename().string()},
                        {"overlay_epi_horizontal", epi_h_path.filename().string()},
                        {"overlay_epi_vertical", epi_v_path.filename().string()},
                        {"epi_row", row},
                        {"epi_column", column}};
  if (!options.labels_png.empty()) summary["outputs"]["labels_png"] = options.labels_png.string();
  summary["parameters"] = segment::ToJson(options.params);
  summary["superpixels"] = lfsp.superpixels;
  summary["effective_label_ratio"] = segment::EffectiveLabelRatio(lfsp.labels);
  summary["noise_sigma"] = lfsp.noise_sigma;
  summary["presmooth"] = lfsp.presmooth;
  summary["iterations"] = lfsp.iterations_run;
  summary["label_moves"] = lfsp.label_moves;
  summary["moves_per_iteration"] = lfsp.moves_per_iteration;
  summary["timings_seconds"] = {{"lab", lfsp.timings.lab_seconds},
                                {"initial", lfsp.timings.initial_seconds},
                                {"projection", lfsp.timings.projection_seconds},
                                {"refine", lfsp.timings.refine_seconds},
                                {"refine_sweeps", lfsp.sweep_seconds},
                                {"refine_planes", lfsp.timings.plane_seconds},
                                {"carry", lfsp.timings.carry_seconds},
                                {"segmentation", lfsp.timings.total_seconds},
                                {"write", write_seconds},
                                {"stage", stopwatch.Seconds()}};
  WriteJsonSummary(summary, SummaryPathFor(out));
  side_outputs.Complete();
  result.summary = std::move(summary);
  return result;
}

}  // namespace lfsp::stages
