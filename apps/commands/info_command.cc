// `lfsp info PATH`: what a light field, disparity map or camera file holds.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>

#include "command_registry.h"
#include "input_loading.h"
#include "lfsp/core/error.h"
#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/stats.h"
#include "lfsp/decode/container_info.h"
#include "lfsp/decode/raw_input.h"
#include "raw_input_options.h"

namespace lfsp::cli {
namespace {

struct InfoOptions {
  std::string path;
  bool json = false;
  int eslf_nu = 0;
  int eslf_nv = 0;
  std::string extract_dir;  // Lytro inputs: write the embedded items here
  PlainRawArguments plain;  // with --camera, a .png/.tif/.jpg is a plain raw Bayer image
};

nlohmann::ordered_json StatsJson(const ValueStats& stats) {
  nlohmann::ordered_json out = {{"min", stats.min}, {"max", stats.max}, {"mean", stats.mean}};
  if (stats.non_finite > 0) out["non_finite"] = stats.non_finite;
  return out;
}

nlohmann::ordered_json DescribeDisparity(const DisparityMap& disparity) {
  return {
      {"width", disparity.width()}, {"height", disparity.height()}, {"values", StatsJson(DisparityStats(disparity))}};
}

nlohmann::ordered_json DescribeBundle(const Bundle& bundle, LightFieldFormat format) {
  const LightField& light_field = bundle.light_field;
  const LightFieldShape& shape = light_field.shape();
  static const char* kFormatNames[] = {"views folder", "HDF5 bundle", "ESLF image", "MATLAB .mat (LF(v,u,y,x,c))"};
  nlohmann::ordered_json out;
  out["format"] = kFormatNames[static_cast<int>(format)];
  out["views"] = {{"nu", shape.nu}, {"nv", shape.nv}};
  out["view_size"] = {{"width", shape.width}, {"height", shape.height}, {"channels", shape.channels}};
  out["centre_view"] = {{"u", shape.Centre().u}, {"v", shape.Centre().v}};
  out["transfer"] = ToString(light_field.transfer);
  static const char* kChannelNames[] = {"R", "G", "B"};
  for (int c = 0; c < shape.channels; ++c)
    out["value_range"][shape.channels == 3 ? kChannelNames[c] : std::to_string(c)] =
        StatsJson(ChannelStats(light_field, c));
  if (light_field.HasWeights())
    out["weights"] = StatsJson(ComputeStats(light_field.weights().data(), light_field.weights().size()));
  if (const auto range = DisparityRangeFromMetadata(light_field.metadata))
    out["disparity_range"] = {{"min", range->min}, {"max", range->max}, {"source", "metadata"}};
  if (bundle.disparity) out["disparity"] = DescribeDisparity(*bundle.disparity);
  if (bundle.labels) {
    std::set<int> distinct(bundle.labels->data(), bundle.labels->data() + bundle.labels->size());
    distinct.erase(Labels::kUnlabelled);
    out["labels"] = {{"distinct", distinct.size()}};
  }
  if (!light_field.metadata.empty()) out["metadata"] = light_field.metadata;
  return out;
}

void PrintReadable(const nlohmann::ordered_json& info, const std::string& path) {
  std::printf("%s\n", path.c_str());
  if (info.contains("views")) {
    std::printf("  format       %s\n", info["format"].get<std::string>().c_str());
    std::printf("  views        %d x %d (nu x nv), centre (u=%d, v=%d)\n", info["views"]["nu"].get<int>(),
                info["views"]["nv"].get<int>(), info["centre_view"]["u"].get<int>(),
                info["centre_view"]["v"].get<int>());
    std::printf("  view size    %d x %d, %d channels\n", info["view_size"]["width"].get<int>(),
                info["view_size"]["height"].get<int>(), info["view_size"]["channels"].get<int>());
    std::printf("  transfer     %s\n", info["transfer"].get<std::string>().c_str());
    for (const auto& [channel, stats] : info["value_range"].items())
      std::printf("  channel %-4s min %.4f  max %.4f  mean %.4f\n", channel.c_str(), stats["min"].get<double>(),
                  stats["max"].get<double>(), stats["mean"].get<double>());
    if (info.contains("weights"))
      std::printf("  weights      min %.4f  max %.4f\n", info["weights"]["min"].get<double>(),
                  info["weights"]["max"].get<double>());
    if (info.contains("disparity_range"))
      std::printf("  disparity range (metadata) %.3f .. %.3f px/view\n", info["disparity_range"]["min"].get<double>(),
                  info["disparity_range"]["max"].get<double>());
    if (info.contains("labels"))
      std::printf("  labels       %zu distinct\n", info["labels"]["distinct"].get<std::size_t>());
  }
  if (info.contains("disparity")) {
    const auto& disparity = info["disparity"];
    std::printf("  disparity map %d x %d, min %.4f  max %.4f  mean %.4f\n", disparity["width"].get<int>(),
                disparity["height"].get<int>(), disparity["values"]["min"].get<double>(),
                disparity["values"]["max"].get<double>(), disparity["values"]["mean"].get<double>());
  }
  if (info.contains("metadata")) {
    std::printf("  metadata\n");
    for (const auto& [section, values] : info["metadata"].items()) {
      if (!values.is_object()) continue;
      std::printf("    [%s]\n", section.c_str());
      for (const auto& [key, value] : values.items()) std::printf("      %s = %s\n", key.c_str(), value.dump().c_str());
    }
  }
}

bool IsPfm(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return extension == ".pfm";
}

// Lytro containers, raw + TXT pairs and white-image metadata are described by the decode library.
void RunLytroInfo(const InfoOptions& options) {
  const std::filesystem::path path(options.path);
  const nlohmann::ordered_json description = decode::DescribeLytroFile(path);
  if (options.json) {
    std::cout << description.dump(2) << std::endl;
  } else {
    std::cout << decode::FormatLytroDescription(description);
  }
  if (!options.extract_dir.empty()) {
    const auto written = decode::ExtractLytroFile(path, options.extract_dir);
    if (!options.json)
      std::cout << "  extracted    " << written.size() << " files into " << options.extract_dir << "\n";
  }
}

// A plain raw Bayer image read as `decode` would read it: size, levels, camera, code statistics per Bayer phase.
void RunPlainRawInfo(const InfoOptions& options) {
  const decode::RawInput input = decode::ReadPlainRawImage(options.path, ToPlainRawOptions(options.plain));
  const decode::RawFormat& format = *input.metadata.raw_format;
  nlohmann::ordered_json info = {{"format", input.format},
                                 {"width", input.raw.width},
                                 {"height", input.raw.height},
                                 {"camera", input.metadata.camera_model},
                                 {"metadata", input.metadata.schema},
                                 {"bayer", std::string(decode::ToString(format.mosaic))},
                                 {"levels", input.levels}};
  for (int phase = 0; phase < 4; ++phase) {
    double sum = 0.0;
    std::uint16_t low = 65535, high = 0;
    long count = 0;
    for (int y = phase / 2; y < input.raw.height; y += 2)
      for (int x = phase % 2; x < input.raw.width; x += 2) {
        const std::uint16_t code = input.raw.at(y, x);
        sum += code;
        low = std::min(low, code);
        high = std::max(high, code);
        ++count;
      }
    info["phases"].push_back({{"phase", phase}, {"min", low}, {"max", high}, {"mean", count ? sum / count : 0.0}});
  }
  if (options.json) {
    std::cout << info.dump(2) << std::endl;
    return;
  }
  std::printf(
      "%s\n  format       %s\n  size         %d x %d\n  camera       %s (%s)\n  bayer        %s\n  levels       %s\n",
      options.path.c_str(), input.format.c_str(), input.raw.width, input.raw.height,
      input.metadata.camera_model.empty() ? "unknown" : input.metadata.camera_model.c_str(),
      input.metadata.schema.c_str(), std::string(decode::ToString(format.mosaic)).c_str(), input.levels.c_str());
  for (const auto& phase : info["phases"])
    std::printf("  phase %d      codes %d .. %d, mean %.1f\n", phase["phase"].get<int>(), phase["min"].get<int>(),
                phase["max"].get<int>(), phase["mean"].get<double>());
}

void RunInfo(const InfoOptions& options) {
  const std::filesystem::path path(options.path);
  if (decode::LooksLikeLytroFile(path)) return RunLytroInfo(options);
  if (!options.plain.camera.empty() || !options.plain.bayer.empty()) {
    if (!decode::IsPlainRawImagePath(path))
      throw Error(path.string() + ": --camera/--bayer describe a plain raw image (.png, .tif, .tiff, .jpg, .jpeg)");
    return RunPlainRawInfo(options);
  }
  if (!options.extract_dir.empty())
    throw Error("--extract applies to Lytro files only; " + path.string() + " is not one");
  nlohmann::ordered_json info;
  if (IsPfm(path)) {
    info["format"] = "PFM disparity map";
    info["disparity"] = DescribeDisparity(ReadPfm(path));
  } else {
    LoadOptions load = GlobalLoadOptions();
    if (options.eslf_nu > 0) load.eslf.nu = options.eslf_nu;
    if (options.eslf_nv > 0) load.eslf.nv = options.eslf_nv;
    const LightFieldFormat format = DetectLightFieldFormat(path);
    info = DescribeBundle(LoadLightField(path, load), format);
  }
  if (options.json) {
    std::cout << info.dump(2) << std::endl;
  } else {
    PrintReadable(info, options.path);
  }
}

void AddInfoCommand(CLI::App& app) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* command = app.add_subcommand(
      "info",
      "Print what a file holds: light field (views folder, .h5 bundle, ESLF .png) dimensions, value ranges, "
      "metadata and disparity range; a disparity .pfm; or a Lytro file (.lfp/.lfr container, calibration "
      "archive, MOD_*.RAW + .TXT pair): sections, SHA-1s, camera, zoom/focus, exposure, what it holds");
  command->add_option("path", options->path, "Views folder, .h5 bundle, ESLF image, .pfm or Lytro file")->required();
  command->add_flag("--json", options->json, "Print JSON instead of text (default: text)");
  command->add_option("--eslf-nu", options->eslf_nu, "Angular columns of an ESLF without lfsp attributes (e.g. 14)");
  command->add_option("--eslf-nv", options->eslf_nv, "Angular rows of an ESLF without lfsp attributes (e.g. 14)");
  command->add_option("--extract", options->extract_dir,
                      "Lytro files: write the embedded items (JPEG frames, depth maps as PFM, metadata JSON, raw "
                      "payloads) into this folder (default: none, nothing written)");
  AddPlainRawOptions(command, options->plain);
  command->callback([options] { RunInfo(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(10, "info", AddInfoCommand);

}  // namespace lfsp::cli
