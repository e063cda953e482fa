// `lfsp segment LF --disparity DISP.pfm --out OUT.h5`: light-field superpixels (LFSP) of a light field (views folder
// or .h5 bundle) given a centre-view disparity. Writes OUT.h5 (the light field, the disparity used and `labels`
// nv x nu x H x W), OUT.planes.json (one slanted plane per label), boundary overlays of the centre view and of a
// horizontal and a vertical EPI (OUT.overlay_centre.png, OUT.overlay_epi_h.png, OUT.overlay_epi_v.png),
// optionally 16-bit label PNGs per view, and OUT.summary.json.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <memory>
#include <string>

#include "command_registry.h"
#include "input_loading.h"
#include "lfsp/core/error.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "lfsp/segment/lfsp.h"
#include "lfsp/segment/metrics.h"
#include "lfsp/segment/output.h"
#include "summary.h"
#include "view_selection.h"

namespace lfsp::cli {
namespace {

struct SegmentCommandOptions {
  int views = 0;
  std::string input;
  std::string disparity;
  std::string output;
  std::string labels_png;
  int epi_row = -1;
  int epi_column = -1;
  segment::LfspParams params;
};

std::filesystem::path Beside(const std::filesystem::path& output, const std::string& suffix) {
  std::filesystem::path path = output;
  path.replace_extension();
  return path.string() + suffix;
}

void RunSegment(const SegmentCommandOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  Bundle bundle = LoadInput(options.input);
  const nlohmann::json views = SelectViews(bundle, options.views, options.input);
  DisparityMap disparity;
  std::string disparity_source;
  if (!options.disparity.empty()) {
    disparity = ReadPfm(options.disparity);
    disparity_source = options.disparity;
  } else if (bundle.disparity) {
    disparity = *bundle.disparity;
    disparity_source = options.input + " (its own disparity)";
  } else {
    throw Error(options.input + ": no disparity in the input; give --disparity DISP.pfm");
  }
  const LightFieldShape shape = bundle.light_field.shape();
  spdlog::info("{}: {}, disparity from {}", options.input, ToString(shape), disparity_source);
  const segment::LfspResult result = segment::SegmentLightField(bundle.light_field, disparity, options.params);
  spdlog::info("{} superpixels, {} label moves in {} iterations ({:.2f} s)", result.superpixels, result.label_moves,
               result.iterations_run, result.timings.total_seconds);

  const std::filesystem::path out = options.output;
  const int row = options.epi_row >= 0 ? options.epi_row : shape.height / 2;
  const int column = options.epi_column >= 0 ? options.epi_column : shape.width / 2;
  const std::filesystem::path planes_path = Beside(out, ".planes.json");
  const std::filesystem::path centre_path = Beside(out, ".overlay_centre.png");
  const std::filesystem::path epi_h_path = Beside(out, ".overlay_epi_h.png");
  const std::filesystem::path epi_v_path = Beside(out, ".overlay_epi_v.png");
  segment::WritePng(segment::CentreOverlay(bundle.light_field, result.labels), centre_path);
  segment::WritePng(segment::HorizontalEpiOverlay(bundle.light_field, result.labels, row), epi_h_path);
  segment::WritePng(segment::VerticalEpiOverlay(bundle.light_field, result.labels, column), epi_v_path);
  WriteJsonSummary(segment::PlanesToJson(result.planes), planes_path);
  if (!options.labels_png.empty()) segment::WriteLabelPngs(result.labels, options.labels_png);

  // The bundle is self-contained for `lfsp evaluate segmentation`: light field, the disparity LFSP used, labels,
  // and the parameters in the metadata (for the refocus sweep).
  Bundle labelled;
  labelled.light_field = std::move(bundle.light_field);
  labelled.light_field.metadata["lfsp_segment"] = segment::SegmentationRecord(options.params, disparity_source);
  labelled.disparity = disparity;
  labelled.labels = result.labels;
  WriteBundle(labelled, out, CompactBundleOptions(labelled.light_field));

  nlohmann::json summary;
  summary["command"] = "segment";
  summary["input"] = options.input;
  summary["views"] = views;
  summary["disparity"] = disparity_source;
  summary["shape"] = ToString(shape);
  summary["outputs"] = {{"bundle", out.string()},
                        {"planes", planes_path.string()},
                        {"overlay_centre", centre_path.string()},
                        {"overlay_epi_horizontal", epi_h_path.string()},
                        {"overlay_epi_vertical", epi_v_path.string()},
                        {"epi_row", row},
                        {"epi_column", column}};
  if (!options.labels_png.empty()) summary["outputs"]["labels_png"] = options.labels_png;
  summary["parameters"] = segment::ToJson(options.params);
  summary["superpixels"] = result.superpixels;
  summary["effective_label_ratio"] = segment::EffectiveLabelRatio(result.labels);
  summary["noise_sigma"] = result.noise_sigma;
  summary["presmooth"] = result.presmooth;
  summary["iterations"] = result.iterations_run;
  summary["label_moves"] = result.label_moves;
  summary["moves_per_iteration"] = result.moves_per_iteration;
  summary["timings_seconds"] = {
      {"lab", result.timings.lab_seconds},
      {"initial", result.timings.initial_seconds},
      {"projection", result.timings.projection_seconds},
      {"refine", result.timings.refine_seconds},
      {"cleanup", result.timings.cleanup_seconds},
      {"segmentation", result.timings.total_seconds},
      {"command", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()}};
  WriteJsonSummary(summary, SummaryPathFor(out));
  spdlog::info("wrote {}", out.string());
}

// Adds --name for one numeric parameter, documenting its default.
template <typename T>
void AddParameter(CLI::App* command, const std::string& name, T& value, const std::string& help) {
  command->add_option(name, value, help)->capture_default_str();
}

void AddSegmentCommand(CLI::App& parent) {
  auto options = std::make_shared<SegmentCommandOptions>();
  segment::LfspParams& p = options->params;
  CLI::App* command = parent.add_subcommand(
      "segment",
      "Light-field superpixels (LFSP, Zhu et al. TIP 2020): consistent labels for every ray of every view; writes "
      "OUT.h5 (labels nv x nu x H x W), OUT.planes.json, boundary overlays (centre view, EPIs), OUT.summary.json");
  command->add_option("input", options->input, "Light field: views folder (HCI style) or .h5 bundle")
      ->required()
      ->check(CLI::ExistingPath);
  command
      ->add_option("--disparity", options->disparity,
                   "Centre-view disparity (PFM, HCI convention); default: the input's own (gt_disp_lowres.pfm "
                   "beside the views, or the bundle's dataset)")
      ->check(CLI::ExistingFile);
  command->add_option("--out", options->output, "Output bundle (.h5)")->required();
  AddViewsOption(command, options->views);
  command->add_option("--labels-png", options->labels_png,
                      "Also write label_Cam%03d.png (16-bit, one per view) into this folder (default: none)");
  command->add_option("--epi-row", options->epi_row, "Image row of the horizontal EPI overlay (default: middle)");
  command->add_option("--epi-column", options->epi_column,
                      "Image column of the vertical EPI overlay (default: middle)");
  AddParameter(command, "--size", p.size, "Superpixel size: seed grid step in the centre view, pixels");
  AddParameter(command, "--lambda-p", p.lambda_p, "Position weight lambda_p (Table II)");
  AddParameter(command, "--lambda-d", p.lambda_d, "Disparity weight lambda_d (Table II)");
  AddParameter(command, "--lambda-s", p.lambda_s, "Plane smoothness weight lambda_s (Table II)");
  AddParameter(command, "--lambda-b", p.lambda_b, "Boundary weight lambda_b (Table II)");
  AddParameter(command, "--pen-spatial", p.pen_spatial, "Spatial-neighbour penalty E_pen_s (Table II)");
  AddParameter(command, "--pen-mixed", p.pen_mixed, "Mixed-neighbour penalty E_pen_m (Table II)");
  AddParameter(command, "--pen-angular", p.pen_angular, "Angular-neighbour penalty E_pen_a (Table II)");
  AddParameter(command, "--colour-scale", p.colour_scale, "Lab distance worth one unit of energy");
  AddParameter(command, "--slic-iterations", p.slic_iterations, "Iterations of the initial centre-view SLIC");
  AddParameter(command, "--iterations", p.iterations,
               "Outer block-coordinate-descent iterations (0 = projection only)");
  AddParameter(command, "--plane-iterations", p.plane_iterations, "Plane-smoothing rounds per outer iteration");
  AddParameter(command, "--inlier-threshold", p.inlier_threshold,
               "Disparity residual (px) above which a pixel does not pull its plane");
  AddParameter(command, "--hinge-penalty", p.hinge_penalty, "Cost of a hinge boundary (px^2)");
  AddParameter(command, "--occlusion-penalty", p.occlusion_penalty, "Cost of an occlusion boundary (px^2)");
  AddParameter(command, "--impossible-penalty", p.impossible_penalty,
               "Extra cost when an occlusion's claimed front is behind (px^2)");
  AddParameter(command, "--convergence", p.convergence,
               "Stop when fewer than this fraction of rays changed label in an iteration");
  AddParameter(command, "--presmooth", p.presmooth,
               "Gaussian smoothing (px) of the colours compared, against noise; -1 = from the estimated noise "
               "(none on clean views, up to 1.5 px), 0 = off");
  AddParameter(command, "--threads", p.threads, "OpenMP threads (0 = all)");
  command->callback([options] {
    segment::Validate(options->params);
    RunSegment(*options);
  });
}

}  // namespace

LFSP_REGISTER_COMMAND(80, "segment", AddSegmentCommand);

}  // namespace lfsp::cli
