// `lfsp pipeline [INPUT] --out DIR`: the whole chain on one input, ending with report.html.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>

#include "../pipeline/pipeline.h"
#include "arguments/decode_arguments.h"
#include "command_registry.h"
#include "raw_input_options.h"
#include "shell_quoting.h"
#include "view_selection.h"

namespace lfsp::cli {
namespace {

void AddPipelineCommand(CLI::App& app) {
  auto options = std::make_shared<pipeline::PipelineOptions>();
  auto input = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  CLI::App* command = app.add_subcommand(
      "pipeline",
      "Run everything on one input: (decode) -> depth -> LFSP segmentation -> (recolour) -> evaluation -> report.html");
  command->add_option("input", *input,
                      "Lytro capture (.lfr/.lfp, with white images), plain raw PNG/TIFF/JPEG with --camera, or light "
                      "field (views folder, .h5 bundle, ESLF); "
                      "default: the bundled mini-Illum capture");
  command->add_option("--out", *out, "Output folder for every intermediate, summary.json and report.html")->required();
  AddViewsOption(command, options->views);
  command->add_option("--white-images", options->white_images,
                      "Folder of white images for a raw capture (default: beside the capture, and its whites/)");
  command->add_flag("--no-white-image", options->no_white_image,
                    "Raw captures: estimate the white image and lenslet grid from the capture itself (automatic, with "
                    "a warning, when no white image matches)");
  auto grid_file = std::make_shared<std::string>();
  AddGridFileOption(command, *grid_file);
  auto plain = std::make_shared<PlainRawArguments>();
  AddPlainRawOptions(command, *plain);
  auto dmin = std::make_shared<float>(0.0f);
  auto dmax = std::make_shared<float>(0.0f);
  CLI::Option* dmin_option = command->add_option(
      "--dmin", *dmin,
      "Smallest disparity to consider (px/view); "
      "default: the input's metadata, else its ground truth (padded), else estimated from the views");
  CLI::Option* dmax_option = command->add_option("--dmax", *dmax, "Largest disparity to consider (px/view)");
  dmin_option->needs(dmax_option);
  dmax_option->needs(dmin_option);
  command->add_option("--size", options->segment.size, "Superpixel size (seed grid step, px)")
      ->capture_default_str()
      ->check(CLI::Range(4, 200));
  command->add_option("--depth-labels", options->depth.labels, "Disparity labels of the depth cost volume")
      ->capture_default_str()
      ->check(CLI::Range(8, 512));
  command->add_option("--recolor", options->recolor,
                      "Recolour superpixels, e.g. \"at=120,80;hue=140\" or \"ids=3+17;saturation=0\" (keys: at, ids, "
                      "hue, saturation, value, feather, space); default: no recolouring");
  command
      ->add_option("--focal-stack", options->focal_stack_slices, "Slices of the focal stack over the disparity range")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  command->callback([options, input, out, dmin, dmax, dmin_option, plain, grid_file] {
    options->plain = ToPlainRawOptions(*plain);
    options->grid = *grid_file;
    if (dmin_option->count() > 0) options->depth.range = DisparityRange{*dmin, *dmax};
    options->input = *input;
    options->out = *out;
    const pipeline::PipelineResult result = pipeline::RunPipeline(*options);
    std::printf("report: %s\n", result.report.string().c_str());
    // The interactive counterpart of the report: every view, selection and editing in the browser.
    std::printf("view:   %s\n", ShellQuoted({"lfsp", "view", options->out.string()}).c_str());
  });
}

}  // namespace

LFSP_REGISTER_COMMAND(130, "pipeline", AddPipelineCommand);

}  // namespace lfsp::cli
