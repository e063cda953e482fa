// `lfsp recolor LF --labels LABELS.h5 (--label-ids ... | --at x,y ... | --mask MASK.png) --out OUT`: change hue,
// saturation and value of chosen light-field superpixels in every view at once.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "arguments/recolor_arguments.h"
#include "command_registry.h"
#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/edit/selection.h"
#include "recolor_request.h"
#include "stages/recolor_stage.h"
#include "view_selection.h"

namespace lfsp::cli {
namespace {

namespace fs = std::filesystem;

// The request by label ids, with the command's other ways to choose.
struct RecolorCommandOptions : RecolorRequest {
  std::vector<std::string> at;
  std::string mask;
};

std::vector<std::int32_t> ChooseSelection(const RecolorCommandOptions& options, const Labels& labels,
                                          nlohmann::ordered_json& how) {
  const int ways = (options.label_ids.empty() ? 0 : 1) + (options.at.empty() ? 0 : 1) + (options.mask.empty() ? 0 : 1);
  if (ways != 1) throw Error("choose the superpixels in exactly one way: --label-ids, --at or --mask");
  if (!options.label_ids.empty()) {
    how = {{"by", "label-ids"}, {"label_ids", options.label_ids}};
    return edit::SelectLabelIds(labels, options.label_ids);
  }
  if (!options.at.empty()) {
    std::vector<cv::Point> points;
    for (const std::string& text : options.at) points.push_back(edit::ParseViewPoint(text, "--at"));
    how = {{"by", "at"}, {"points", options.at}};
    return edit::SelectAtPoints(labels, points);
  }
  how = {{"by", "mask"}, {"mask", options.mask}, {"min_area_fraction", 0.5}};
  return edit::SelectByMask(labels, ReadImage(options.mask).pixels, 0.5);
}

void RunRecolor(const RecolorCommandOptions& options) {
  const Stopwatch stopwatch;
  stages::RecolorStageOptions stage;
  stage.recolor = RecolorOptionsOf(options);
  stage.bit_depth = options.bit_depth;
  std::error_code ec;
  if (fs::exists(options.out, ec) && fs::equivalent(options.input, options.out, ec))
    throw Error("--out " + options.out + " is the input: inputs are never modified, choose another path");

  nlohmann::ordered_json summary = {{"command", "recolor"}, {"input", options.input}};
  Bundle bundle = LoadLabelledInput(options, summary);
  summary["load_seconds"] = stopwatch.Seconds();
  stage.selection = ChooseSelection(options, *bundle.labels, stage.how);
  spdlog::info("selected {} superpixel(s)", stage.selection.size());
  stages::RunRecolorStage(bundle, stage, options.out, std::move(summary));
}

void AddRecolorCommand(CLI::App& app) {
  auto options = std::make_shared<RecolorCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "recolor",
      "Recolour light-field superpixels chosen in the centre view (by id, by clicking points or by a mask): change "
      "hue, saturation and value in every view at once. Rays outside the selection and its feather band are left "
      "bit-identical. Writes the new light field, before/after previews of the centre view and a JSON summary");
  command->add_option("light_field", options->input, "Input light field (views folder, .h5 bundle or ESLF .png)")
      ->required();
  AddViewsOption(command, options->views);
  command->add_option("--labels", options->labels,
                      "HDF5 file with per-ray labels, dataset 'labels' (nv x nu x H x W int32, as `lfsp segment` "
                      "writes it) or 'GT_LABELS' (default: the input bundle's own labels)");
  command
      ->add_option("--label-ids", options->label_ids,
                   "Select these label ids, comma-separated, e.g. 3,17 (give exactly one of --label-ids, --at, --mask)")
      ->delimiter(',')
      ->allow_extra_args(false);  // one value per occurrence: never swallow the positional light field
  command
      ->add_option("--at", options->at,
                   "Select the label under this centre-view pixel x,y (column,row); repeat for several, e.g. "
                   "--at 120,88 --at 40,200 (default: none)")
      ->allow_extra_args(false);  // one value per occurrence: never swallow the positional light field
  command->add_option("--mask", options->mask,
                      "Select the labels with more than half of their centre-view area inside this mask image "
                      "(centre-view size; white = inside) (default: none)");
  AddRecolorArguments(command, options->colour_edit);
  command->add_option("--bit-depth", options->bit_depth,
                      "Bits per sample of a views-folder or ESLF output (previews are 8-bit): 8 or 16 (default: 8)");
  command
      ->add_option(
          "--out", options->out,
          "Output light field: .h5 bundle (float, exact), .png ESLF or a views folder; "
          "the previews OUT-stem.before.png and OUT-stem.after.png go beside it, the summary to OUT.summary.json "
          "(OUT/summary.json for a folder)")
      ->required();
  command->callback([options] { RunRecolor(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(120, "recolor", AddRecolorCommand);

}  // namespace lfsp::cli
