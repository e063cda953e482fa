// `lfsp view INPUT [--labels SEG.h5] [--disparity D.pfm] [--port N]`: the interactive viewer and superpixel editor,
// a page served to the local browser.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <string>

#include "command_registry.h"
#include "lfsp/core/stopwatch.h"
#include "view/viewer_data.h"
#include "view/viewer_server.h"

namespace lfsp::cli {
namespace {

struct ViewCommandOptions {
  std::string input;
  std::string labels;
  std::string disparity;
  view::ServerOptions server;
};

void RunView(const ViewCommandOptions& options) {
  const view::ViewerSources sources = view::ResolveSources(options.input, options.labels, options.disparity);
  const Stopwatch stopwatch;
  const view::ViewerData data = view::LoadViewerData(sources);
  spdlog::info("loaded {} in {:.1f} s", ToString(data.bundle.light_field.shape()), stopwatch.Seconds());
  view::ServerOptions server = options.server;
  server.export_folder = std::filesystem::absolute(server.export_folder);
  view::Serve(data, server, [&](int port) {
    // On stdout, one line, so scripts (and the browser test) can read the address.
    std::printf("lfsp view: http://%s:%d/ (exports go to %s; Ctrl-C stops)\n", server.host.c_str(), port,
                server.export_folder.string().c_str());
    std::fflush(stdout);
  });
}

void AddViewCommand(CLI::App& app) {
  auto options = std::make_shared<ViewCommandOptions>();
  options->server.export_folder = "lfsp-view-export";
  CLI::App* command = app.add_subcommand(
      "view",
      "Interactive viewer and superpixel editor in the browser: move through the views with their EPIs, show depth "
      "and superpixel boundaries, select superpixels (click, shift-click, paint, similar depth), preview hue / "
      "saturation / value edits in every view and refocusing, and export with `lfsp recolor`'s own stage");
  command
      ->add_option("input", options->input,
                   "Light field (views folder, .h5 bundle, ESLF .png, .mat) or a `lfsp pipeline` output folder "
                   "(its segmentation.h5 and disparity.pfm)")
      ->required();
  command->add_option("--labels", options->labels,
                      "HDF5 file with per-ray labels, as `lfsp segment` writes it (default: the input's own; without "
                      "labels the page only views)");
  command->add_option("--disparity", options->disparity,
                      "Centre-view disparity (PFM) to show; its _confidence.pfm beside it is shown too (default: "
                      "the input's own)");
  command->add_option("--port", options->server.port, "TCP port; 0 = any free port (default: 8765)")
      ->check(CLI::Range(0, 65535));
  command->add_option("--host", options->server.host,
                      "Address to listen on; anything but 127.0.0.1 lets other machines edit and export "
                      "(default: 127.0.0.1)");
  command->add_option("--out", options->server.export_folder,
                      "Folder the page's export writes into: recolored.h5 (+ previews, summary), selection.json, "
                      "selection_mask.png (default: lfsp-view-export)");
  command->callback([options] { RunView(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(140, "view", AddViewCommand);

}  // namespace lfsp::cli
