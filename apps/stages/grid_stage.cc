#include "stages/grid_stage.h"

#include <optional>

#include "lfsp/core/error.h"
#include "lfsp/core/stopwatch.h"

namespace lfsp::stages {
namespace {

std::optional<decode::GridGuess> GuessFor(const decode::RawInput& input) {
  if (!input.metadata.mla) return std::nullopt;
  return decode::GuessFromMetadata(input.metadata, input.raw.width, input.raw.height);
}

}  // namespace

GridStageResult RunGridStage(const std::filesystem::path& path, const std::string& kind_name,
                             const decode::PlainRawOptions& plain) {
  const Stopwatch stopwatch;
  decode::LensletImageKind kind = decode::LensletImageKindFromString(kind_name);
  const decode::RawInput input = decode::OpenRawInput(path, plain);
  if (kind == decode::LensletImageKind::kAuto && input.white_image) kind = decode::LensletImageKind::kWhiteImage;
  if (kind == decode::LensletImageKind::kAuto && !decode::IsPlainRawImagePath(input.path))
    kind = decode::LensletImageKind::kCapture;  // a Lytro capture
  const cv::Mat grey = decode::WhiteImageToGrey(input.raw, *input.metadata.raw_format, path.string());
  GridStageResult result;
  try {
    result.grid = decode::FindLensletGrid(grey, GuessFor(input), kind).grid;
  } catch (const Error& e) {
    throw Error(path.string() + ": " + e.what());
  }
  result.document = {{"input", path.string()},
                     {"format", input.format},
                     {"metadata", input.metadata.schema},
                     {"kind", std::string(decode::ToString(kind))},
                     {"grid", result.grid.ToJson()},
                     {"seconds", stopwatch.Seconds()}};
  return result;
}

}  // namespace lfsp::stages
