// `lfsp noise-study --out DIR`: segmentation quality of LFSP and the per-view baselines against noise level.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>

#include "../noise_study/noise_study.h"
#include "command_registry.h"

namespace lfsp::cli {
namespace {

void AddNoiseStudyCommand(CLI::App& app) {
  auto options = std::make_shared<noise_study::NoiseStudyOptions>();
  auto out = std::make_shared<std::string>();
  CLI::App* command = app.add_subcommand(
      "noise-study",
      "Add noise at increasing levels (Gaussian image noise on an ideal light field; low light at the sensor through "
      "decode) and score LFSP and per-view SLIC/LSC at each: noise_study.csv, summary.json, plot_*.png");
  command->add_option("--out", *out, "Output folder")->required();
  command->add_option("--scene", options->scene, "Built-in scene (lfsp simulate --list-scenes) or scene JSON")
      ->capture_default_str();
  command->add_option("--views", options->views, "Ideal light field: views per axis")->capture_default_str();
  command->add_option("--width", options->width, "Ideal light field: view width")->capture_default_str();
  command->add_option("--height", options->height, "Ideal light field: view height")->capture_default_str();
  command->add_option("--sigmas", options->sigmas, "Gaussian noise levels (standard deviation, samples in [0, 1])")
      ->capture_default_str()
      ->delimiter(',');
  command
      ->add_option("--camera", options->camera,
                   "Camera of the low-light captures (illum, f01, or mini-illum / mini-f01 for a quick run)")
      ->capture_default_str();
  command
      ->add_option("--exposures", options->exposures,
                   "Low-light exposures, fractions of the white level; the first is the reference brightness")
      ->capture_default_str()
      ->delimiter(',');
  command
      ->add_option("--capture-views", options->capture_views,
                   "Central N x N views kept of each decoded capture (the outer ones are vignetted); 0 = all")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command->add_option("--size", options->size, "Superpixel size on the ideal light field")->capture_default_str();
  command->add_option("--capture-size", options->capture_size, "Superpixel size on the decoded captures")
      ->capture_default_str();
  command->add_flag("!--no-lsc", options->lsc, "Leave out per-view LSC (the slowest baseline)");
  command->add_option("--seed", options->seed, "Noise seed")->capture_default_str();
  command->callback([options, out] {
    options->out = *out;
    const noise_study::NoiseStudyResult result = noise_study::RunNoiseStudy(*options);
    std::printf("noise study: %s/noise_study.csv, summary.json and %zu plots\n", out->c_str(), result.plots.size());
  });
}

}  // namespace

LFSP_REGISTER_COMMAND(100, "noise-study", AddNoiseStudyCommand);

}  // namespace lfsp::cli
