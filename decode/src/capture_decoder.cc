#include "lfsp/decode/capture_decoder.h"

#include <spdlog/spdlog.h>

#include <chrono>

#include "lfsp/core/error.h"
#include "lfsp/decode/lenslet_grid.h"
#include "lfsp/decode/lytro_capture.h"
#include "lfsp/decode/white_database.h"

namespace lfsp::decode {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

CaptureDecodeResult DecodeCaptureFile(const std::filesystem::path& capture_path, const CaptureDecodeOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const LytroCapture capture = OpenLytroCapture(capture_path);
  (void)capture.RawBytes();  // "<file>: no raw image: this file holds ..." for exports without one
  if (capture.IsWhiteImage())
    throw Error(capture_path.string() +
                ": this is a white (modulation) image, not a capture; index it with `lfsp whites build` instead");
  if (!capture.metadata) throw Error(capture_path.string() + ": no frame metadata (" + capture.metadata_problem + ")");
  const LytroMetadata& metadata = *capture.metadata;
  const RawImage raw = capture.ReadRawImage();
  const double read_seconds = SecondsSince(start);

  // The white image: by serial, zoom, focus.
  auto step = std::chrono::steady_clock::now();
  const std::filesystem::path white_dir =
      options.white_images.empty() ? std::filesystem::absolute(capture_path).parent_path() : options.white_images;
  if (!std::filesystem::is_directory(white_dir))
    throw Error(white_dir.string() + ": white-image folder does not exist");
  const WhiteImageDatabase database = LoadOrBuildWhiteImageDatabase(white_dir);
  const WhiteImageChoice choice = SelectWhiteImage(database, metadata);
  spdlog::info("white image: {}", choice.explanation);
  const RawImage white = ReadWhiteImageRaw(*choice.entry);
  const LytroMetadata white_metadata = ReadWhiteImageMetadata(*choice.entry);
  const double white_seconds = SecondsSince(step);

  // The lenslet grid, fitted on the white image, starting from its micro-lens description (or the capture's).
  step = std::chrono::steady_clock::now();
  const PreparedWhite prepared = PrepareWhite(white, white_metadata, options.decode.colour, options.decode.min_white);
  const LytroMetadata& mla_source = white_metadata.mla ? white_metadata : metadata;
  const GridEstimate estimate =
      EstimateLensletGrid(prepared.grey, GuessFromMetadata(mla_source, white.width, white.height));
  const double grid_seconds = SecondsSince(step);
  spdlog::info("lenslet grid: {} x {} lenses, spacing {:.4f} x {:.4f} px, rotation {:.6f} rad, fit rms {:.4f} px",
               estimate.grid.columns, estimate.grid.rows, estimate.grid.spacing_x, estimate.grid.spacing_y,
               estimate.grid.rotation, estimate.grid.rms_residual);

  CaptureDecodeResult result;
  DecodeReport report;
  result.light_field = DecodeLenslet(raw, metadata, prepared, estimate.grid, options.decode, &report);
  result.light_field.metadata["decode"]["white_choice"] = choice.explanation;

  const LightFieldShape& shape = result.light_field.shape();
  result.summary = {
      {"capture", capture_path.string()},
      {"camera", {{"model", metadata.camera_model}, {"serial", metadata.serial}}},
      {"white_image",
       {{"name", choice.entry->name}, {"path", choice.entry->raw_path.string()}, {"why", choice.explanation}}},
      {"grid", estimate.grid.ToJson()},
      {"light_field",
       {{"nu", shape.nu},
        {"nv", shape.nv},
        {"width", shape.width},
        {"height", shape.height},
        {"transfer", ToString(result.light_field.transfer)}}},
      {"decode", report.ToJson()},
      {"seconds",
       {{"read", read_seconds},
        {"white_image", white_seconds},
        {"white_preparation_and_grid", grid_seconds},
        {"total", SecondsSince(start)}}}};
  return result;
}

}  // namespace lfsp::decode
