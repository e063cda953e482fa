// `lfsp pipeline [INPUT] --out DIR`: the whole chain on one input, ending with report.html.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>

#include "../pipeline/pipeline.h"
#include "command_registry.h"

namespace lfsp::cli {
namespace {

void AddPipelineCommand(CLI::App& app) {
  auto options = std::make_shared<pipeline::PipelineOptions>();
  auto input = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  CLI::App* command = app.add_subcommand(
      "pipeline",
      "Run everything on one input: (decode) -> depth -> LFSP segmentation -> (recolour) -> evaluation -> report.html");
  command->add_option("input", *input, "Light field (views folder or .h5 bundle); default: the bundled sample");
  command->add_option("--out", *out, "Output folder for every intermediate, summary.json and report.html")->required();
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
  command->callback([options, input, out] {
    options->input = *input;
    options->out = *out;
    const pipeline::PipelineResult result = pipeline::RunPipeline(*options);
    std::printf("report: %s\n", result.report.string().c_str());
  });
}

}  // namespace

LFSP_REGISTER_COMMAND(130, "pipeline", AddPipelineCommand);

}  // namespace lfsp::cli
