#include "lfsp/decode/capture_decoder.h"

#include <spdlog/spdlog.h>

#include <optional>
#include <utility>

#include "lfsp/core/error.h"
#include "lfsp/core/memory_usage.h"
#include "lfsp/core/progress.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/decode/given_grid.h"
#include "lfsp/decode/lenslet_grid.h"
#include "lfsp/decode/white_database.h"

namespace lfsp::decode {
namespace {

// The white image a decode uses and where it came from.
struct WhiteSource {
  RawImage raw;
  LytroMetadata metadata;
  nlohmann::json summary;  // name, path, why (and, when estimated, how many lenses it was averaged over)
  bool estimated = false;
  std::optional<LensletGrid> grid;  // fitted on it by `lfsp whites build` and stored in the database
};

// The capture's white image from the database: by serial, zoom, focus. Without a match, nothing (and `why` says
// why); a matching white image that cannot be read is an lfsp::Error, not a reason to fall back.
std::optional<WhiteSource> WhiteFromDatabase(const RawInput& input, const std::filesystem::path& white_dir,
                                             std::string& why) {
  std::optional<WhiteImageChoice> found;
  std::optional<WhiteImageDatabase> database;
  try {
    database = LoadOrBuildWhiteImageDatabase(white_dir);
    found = SelectWhiteImage(*database, input.metadata);
  } catch (const Error& e) {
    why = std::string("no matching white image (") + e.what() + ")";
    return std::nullopt;
  }
  const WhiteImageChoice& choice = *found;
  WhiteSource white;
  white.raw = ReadWhiteImageRaw(*choice.entry);
  white.metadata = ReadWhiteImageMetadata(*choice.entry);
  white.summary = {
      {"name", choice.entry->name}, {"path", choice.entry->raw_path.string()}, {"why", choice.explanation}};
  // Fitted from the white image's own micro-lens description, as the decode would fit it; without one the decode
  // fits from the capture's, which the stored grid did not see. A white image changed since it was indexed is not
  // the one the grid was fitted on.
  if (white.metadata.mla && choice.entry->grid) {
    if (StillAsIndexed(*choice.entry))
      white.grid = choice.entry->grid;
    else
      spdlog::warn(
          "{}: changed since its white-image database was built; fitting its lenslet grid again (lfsp whites "
          "build {} stores it anew)",
          choice.entry->raw_path.string(), choice.entry->raw_path.parent_path().string());
  }
  // A damaged white image is left out of the choice, which may then fall on a farther zoom or focus: say so, since
  // the damaged one may have been the match.
  if (!database->skipped.empty()) {
    spdlog::warn("{}: {} white image file(s) could not be read and were not considered, first {}", white_dir.string(),
                 database->skipped.size(), database->skipped.front());
    white.summary["skipped"] = database->skipped;
  }
  return white;
}

WhiteSource WhiteFromCapture(const RawInput& input, const LensletGrid& grid, const std::string& why) {
  WhiteSource white;
  CaptureWhiteReport report;
  white.raw = EstimateWhiteImageFromCapture(input.raw, input.metadata, grid, &report);
  white.metadata = input.metadata;
  white.metadata.source = input.path.string() + " (white image estimated from the capture)";
  white.estimated = true;
  white.summary = {{"name", "estimated from the capture"},
                   {"path", input.path.string()},
                   {"why", why},
                   {"lenses_used", report.lenses_used},
                   {"lenses", report.lenses},
                   {"tiles", report.tiles},
                   {"shifted_rows_rim_ratio", report.shifted_rows_rim_ratio}};
  return white;
}

// The grid file the user gave, indexed from the optical axis a fitted grid would be indexed from (the white
// image's or the capture's micro-lens description, else the sensor centre), so both index the same lens alike.
GridEstimate GivenGrid(const std::filesystem::path& grid_file, const RawInput& input, const WhiteSource* white) {
  const LytroMetadata& mla_source = white && white->metadata.mla ? white->metadata : input.metadata;
  double axis_x = 0.5 * (input.raw.width - 1), axis_y = 0.5 * (input.raw.height - 1);
  if (mla_source.mla) {
    const GridGuess guess = GuessFromMetadata(mla_source, input.raw.width, input.raw.height);
    axis_x = guess.axis_x;
    axis_y = guess.axis_y;
  }
  GridEstimate estimate;
  estimate.grid = ReadGivenGrid(grid_file, input.raw.width, input.raw.height, axis_x, axis_y);
  return estimate;
}

}  // namespace

CaptureDecodeResult DecodeCaptureFile(const std::filesystem::path& capture_path, const CaptureDecodeOptions& options) {
  const Stopwatch total;
  Stopwatch step;
  RawInput input = OpenRawInput(capture_path, options.plain);  // its raw image is handed to the decode
  if (input.white_image)
    throw Error(capture_path.string() +
                ": this is a white (modulation) image, not a capture; it belongs in a white-image folder");
  if (!input.has_camera_metadata)
    throw Error(capture_path.string() + ": a plain raw image needs " + OptionName("camera") +
                " f01|illum to decode (sensor layout, optics and colour)");
  const LytroMetadata& metadata = input.metadata;
  // Each step's wall seconds, and the process's resident and peak memory after it (MB).
  nlohmann::json seconds, resident, peak;
  const auto lap = [&](const char* name) {
    seconds[name] = step.Lap();
    resident[name] = ResidentMegabytes();
    peak[name] = PeakResidentMegabytes();
  };
  lap("read");
  // Opening the file included unpacking its raw packing: reported apart.
  seconds["read"] = seconds["read"].get<double>() - input.unpack_seconds;
  seconds["unpack"] = input.unpack_seconds;
  Progress progress("decode", 3);  // white image, grid, decode; drawn only on a terminal

  // The white image: from the database, or (asked for, plain images, none found) estimated from the capture.
  const std::filesystem::path white_dir =
      options.white_images.empty() ? std::filesystem::absolute(capture_path).parent_path() : options.white_images;
  if (!options.white_images.empty() && !std::filesystem::is_directory(white_dir))
    throw Error(white_dir.string() + ": white-image folder does not exist");
  std::optional<WhiteSource> white;
  std::string estimate_why = OptionName("no_white_image");
  if (IsPlainRawImagePath(capture_path)) {
    estimate_why = "a plain raw image has no serial, zoom or focus to match a white image by";
  } else if (!options.no_white_image) {
    white = WhiteFromDatabase(input, white_dir, estimate_why);
    if (!white)
      spdlog::warn("{}: {}; estimating the white image from the capture itself", capture_path.string(), estimate_why);
  }
  lap("white_image");
  progress.Tick();

  // The lenslet grid: given by the user, fitted on the white image (starting from its micro-lens description, or the
  // capture's), or found in the capture itself.
  // grid_source says which in the summary: given | database (stored by lfsp whites build) | fitted | capture.
  GridEstimate estimate;
  std::string grid_source;
  std::optional<PreparedWhite> prepared;
  if (!options.grid.empty()) {
    estimate = GivenGrid(options.grid, input, white ? &*white : nullptr);
    grid_source = "given";
  }
  if (white) {
    // The prepared white image's grey version is what the grid is fitted on.
    prepared = PrepareWhite(white->raw, white->metadata, options.decode.colour, options.decode.min_white);
    const LytroMetadata& mla_source = white->metadata.mla ? white->metadata : metadata;
    if (options.grid.empty() && white->grid) {
      estimate.grid = *white->grid;  // the database checked it lies on this white image's sensor
      grid_source = "database";
    } else if (options.grid.empty()) {
      estimate = FitGridOnWhiteImage(prepared->grey, mla_source);
      grid_source = "fitted";
    }
  } else {
    if (options.grid.empty()) {
      try {
        estimate = FindLensletGridInCapture(input.raw, metadata);
      } catch (const Error& e) {
        throw Error(input.path.string() + ": " + e.what());
      }
      grid_source = "capture";
    }
    white = WhiteFromCapture(input, estimate.grid, estimate_why);
    prepared = PrepareWhite(white->raw, white->metadata, options.decode.colour, options.decode.min_white);
  }
  white->raw = RawImage{};  // prepared: the decode needs only its inverse and grey versions from here on
  lap("white_preparation_and_grid");
  progress.Tick();
  spdlog::info("white image: {}", white->summary["why"].get<std::string>());
  const std::string fit = options.grid.empty() ? fmt::format(", fit rms {:.4f} px", estimate.grid.rms_residual) : "";
  spdlog::info("lenslet grid: {} x {} lenses, spacing {:.4f} x {:.4f} px, rotation {:.6f} rad{} ({}{})",
               estimate.grid.columns, estimate.grid.rows, estimate.grid.spacing_x, estimate.grid.spacing_y,
               estimate.grid.rotation, fit, estimate.grid.fit_method,
               grid_source == "database" ? ", stored by lfsp whites build" : "");

  CaptureDecodeResult result;
  DecodeReport report;
  DecodeOptions decode_options = options.decode;
  // A plain raw image's nominal gains belong to another scene's light: its own grey surfaces decide.
  if (!decode_options.white_balance)
    decode_options.white_balance =
        WhiteBalance{IsPlainRawImagePath(capture_path) ? WhiteBalanceMode::kAuto : WhiteBalanceMode::kCamera};
  decode_options.jpeg_block = input.jpeg_block;
  if (!decode_options.estimated_white_balance) decode_options.estimated_white_balance = input.jpeg_scene_grey;
  // Handed over: the capture's and the white image's sensor-size buffers are freed as the decode goes.
  result.light_field =
      DecodeLenslet(std::move(input.raw), metadata, std::move(*prepared), estimate.grid, decode_options, &report);
  progress.Tick();
  progress.Finish();
  result.light_field.metadata["decode"]["white_choice"] = white->summary["why"];
  result.light_field.metadata["decode"]["white_estimated"] = white->estimated;

  const LightFieldShape& shape = result.light_field.shape();
  result.summary = {{"capture", capture_path.string()},
                    {"input_format", input.format},
                    {"levels", input.levels},
                    {"jpeg_restoration", input.jpeg_restoration},
                    {"camera", {{"model", metadata.camera_model}, {"serial", metadata.serial}}},
                    {"white_image", white->summary},
                    {"grid", estimate.grid.ToJson()},
                    {"grid_source", grid_source},
                    {"light_field",
                     {{"nu", shape.nu},
                      {"nv", shape.nv},
                      {"width", shape.width},
                      {"height", shape.height},
                      {"transfer", ToString(result.light_field.transfer)}}},
                    {"decode", report.ToJson()},
                    {"seconds", seconds},
                    {"resident_mb", resident},
                    {"peak_resident_mb", peak}};
  result.summary["seconds"]["total"] = total.Seconds();
  return result;
}

}  // namespace lfsp::decode
