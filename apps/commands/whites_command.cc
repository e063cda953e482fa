// `lfsp whites build DIR` and `lfsp whites select DIR CAPTURE`: the white-image database (issue 4, item 3).

#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "command_registry.h"
#include "lfsp/core/error.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/decode/lytro_capture.h"
#include "lfsp/decode/white_database.h"
#include "stages/summary.h"

namespace lfsp::cli {
namespace {

struct WhitesOptions {
  std::string dir;
  std::string out;
  std::string capture;
  bool json = false;
  bool no_grids = false;
};

void PrintTable(const decode::WhiteImageDatabase& db) {
  std::printf("%-14s %-14s %6s %6s %10s %11s %6s %-10s %s\n", "name", "serial", "zoom", "focus", "exposure_s", "size",
              "mean", "grid_rms", "dark");
  for (const decode::WhiteImageEntry& e : db.entries) {
    const std::string size = std::to_string(e.width) + "x" + std::to_string(e.height);
    char grid[32] = "-";
    if (e.grid) std::snprintf(grid, sizeof grid, "%.4f", e.grid->rms_residual);
    std::printf("%-14s %-14s %6d %6d %10.5f %11s %6.3f %-10s %s\n", e.name.c_str(), e.serial.c_str(), e.zoom_step,
                e.focus_step, e.exposure_duration, size.c_str(), e.mean_level, grid, e.dark ? "dark" : "");
  }
  for (const std::string& skipped : db.skipped) std::printf("skipped: %s\n", skipped.c_str());
}

void RunBuild(const WhitesOptions& options) {
  const Stopwatch stopwatch;
  decode::WhiteImageDatabase db = decode::BuildWhiteImageDatabase(options.dir);
  const int grids = options.no_grids ? 0 : decode::FitWhiteImageGrids(db);
  const std::filesystem::path out = options.out.empty()
                                        ? std::filesystem::path(options.dir) / decode::kWhiteDatabaseFileName
                                        : std::filesystem::path(options.out);
  decode::WriteWhiteImageDatabase(db, out);
  const double seconds = stopwatch.Seconds();
  stages::WriteJsonSummary(
      nlohmann::ordered_json{
          {"command", "whites build"},
          {"inputs", {{"dir", options.dir}}},
          {"outputs", {{"database", out.string()}}},
          {"metrics", {{"white_images", db.entries.size()}, {"grids_fitted", grids}, {"skipped", db.skipped.size()}}},
          {"timings_s", {{"total", seconds}}}},
      stages::SummaryPathFor(out));
  if (options.json) {
    std::cout << decode::WhiteImageDatabaseJson(db, out.parent_path()).dump(2) << std::endl;
  } else {
    PrintTable(db);
    std::printf("%zu white images indexed, %d lenslet grids fitted, into %s (%.2f s)\n", db.entries.size(), grids,
                out.c_str(), seconds);
  }
}

void RunSelect(const WhitesOptions& options) {
  const decode::LytroCapture capture = decode::OpenLytroCapture(options.capture);
  if (!capture.metadata) throw Error(options.capture + ": no frame metadata to match: " + capture.metadata_problem);
  const decode::WhiteImageDatabase db = decode::LoadOrBuildWhiteImageDatabase(options.dir);
  const decode::WhiteImageChoice choice = decode::SelectWhiteImage(db, *capture.metadata);
  if (options.json) {
    std::cout << nlohmann::json{{"capture", options.capture},
                                {"white_image", choice.entry->raw_path.string()},
                                {"member", choice.entry->raw_member},
                                {"grid_stored", choice.entry->grid.has_value()},
                                {"explanation", choice.explanation}}
                     .dump(2)
              << std::endl;
  } else {
    std::printf("%s\n%s\n", choice.entry->raw_path.c_str(), choice.explanation.c_str());
  }
}

void AddWhitesCommand(CLI::App& app) {
  auto options = std::make_shared<WhitesOptions>();
  CLI::App* whites = app.add_subcommand("whites",
                                        "White-image database: index MOD_*.RAW + .TXT pairs and "
                                        "calibration archives; pick the white image for a capture");
  whites->require_subcommand(1);

  CLI::App* build = whites->add_subcommand(
      "build",
      "Index every MOD_*.TXT + .RAW pair and data.C.* archive under DIR (serial, zoom, focus, exposure, "
      "mean level) into DIR/whites.json, with the lenslet grid fitted on each white image (decode then uses it "
      "instead of fitting again)");
  build->add_option("dir", options->dir, "Folder of white images (searched recursively)")->required();
  build->add_option("--out", options->out, "Database file (default: DIR/whites.json)");
  build->add_flag("--json", options->json, "Print the database as JSON instead of a table (default: table)");
  build->add_flag("--no-grids", options->no_grids,
                  "Do not fit the white images' lenslet grids (0.5-1 s per full-size Illum white image); decode "
                  "then fits the grid on every capture (default: fitted)");
  build->callback([options] { RunBuild(*options); });

  CLI::App* select = whites->add_subcommand(
      "select",
      "Say which white image `lfsp decode` would use for CAPTURE, and why (same serial, then nearest "
      "zoom step, then nearest focus step, then longest exposure)");
  select->add_option("dir", options->dir, "Folder of white images (uses DIR/whites.json when up to date)")->required();
  select->add_option("capture", options->capture, "The capture (.lfp/.lfr/.LFR or .RAW + .TXT/.json)")->required();
  select->add_flag("--json", options->json, "Print JSON instead of text (default: text)");
  select->callback([options] { RunSelect(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(30, "whites", AddWhitesCommand);

}  // namespace lfsp::cli
