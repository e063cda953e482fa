// `lfsp grid INPUT --out grid.json [--centres centres.csv]`: the lenslet lattice of a white image or of an
// ordinary capture.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include "command_registry.h"
#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/lenslet_grid.h"
#include "lfsp/decode/raw_input.h"
#include "raw_input_options.h"
#include "stages/grid_stage.h"
#include "stages/summary.h"

namespace lfsp::cli {
namespace {

struct GridCommandOptions {
  std::string input;
  std::string out;
  std::string centres;
  std::string kind = "auto";
  PlainRawArguments plain;
};

// Every lens of the usable grid, `row,col,x,y` (lens indices, then its centre in 0-based pixel coordinates).
void WriteCentres(const decode::LensletGrid& grid, const std::filesystem::path& path) {
  AtomicOutput output(path);
  {
    std::ofstream file(output.temporary());
    file << "row,col,x,y\n";
    char line[96];
    for (int j = 0; j < grid.rows; ++j)
      for (int i = 0; i < grid.columns; ++i) {
        double x = 0.0, y = 0.0;
        grid.Centre(i, j, x, y);
        std::snprintf(line, sizeof line, "%d,%d,%.4f,%.4f\n", j, i, x, y);
        file << line;
      }
    if (!file) throw Error(path.string() + ": cannot write");
  }
  output.Commit();
}

void RunGrid(const GridCommandOptions& options) {
  const stages::GridStageResult result =
      stages::RunGridStage(options.input, options.kind, ToPlainRawOptions(options.plain));
  const decode::LensletGrid& grid = result.grid;
  stages::WriteJsonSummary(result.document, options.out);
  if (!options.centres.empty()) WriteCentres(grid, options.centres);
  const std::string quality =
      grid.fit_method == "capture periodicity"
          ? std::to_string(grid.blocks_used) + " of " + std::to_string(grid.blocks) + " blocks"
          : std::to_string(grid.lenses_used) + " of " + std::to_string(grid.lenses_measured) + " lenses";
  std::printf(
      "%s: lenslet grid %d x %d lenses, spacing %.4f x %.4f px, rotation %.6f rad, fit rms %.3f px (%s, %s, "
      "%.2f s) -> %s\n",
      options.input.c_str(), grid.columns, grid.rows, grid.spacing_x, grid.spacing_y, grid.rotation, grid.rms_residual,
      grid.fit_method.c_str(), quality.c_str(), result.document.at("seconds").get<double>(), options.out.c_str());
}

void AddGridCommand(CLI::App& app) {
  auto options = std::make_shared<GridCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "grid",
      "Find the lenslet lattice of a white image or of an ordinary capture (Lytro file, or a plain raw Bayer "
      "image): spacing, rotation, origin, lens counts; optionally every lens centre as CSV");
  command->add_option("input", options->input, "Lytro capture or white image, or a plain raw PNG/TIFF/JPEG")
      ->required();
  command->add_option("--out", options->out, "The grid as JSON (lattice model, units in README)")->required();
  command->add_option("--centres", options->centres,
                      "Also write every lens centre: CSV with header row,col,x,y (0-based pixel coordinates, pixel "
                      "centres at integers, x = column)");
  command->add_option("--kind", options->kind,
                      "auto | white | capture: how to fit (white: per-lens centroids; capture: lattice periodicity, "
                      "robust to scene content; auto: Lytro white images as white, Lytro captures as capture, "
                      "plain images by how evenly lit their micro-images are) (default: auto)");
  AddPlainRawOptions(command, options->plain);
  command->callback([options] { RunGrid(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(35, "grid", AddGridCommand);

}  // namespace lfsp::cli
