#include "stages/decode_stage.h"

#include "lfsp/core/load.h"
#include "lfsp/core/memory_usage.h"
#include "lfsp/core/stopwatch.h"
#include "stages/summary.h"

namespace lfsp::stages {

DecodeStageResult RunDecodeStage(const std::filesystem::path& capture, const decode::CaptureDecodeOptions& options,
                                 const std::filesystem::path& out, int bit_depth, const nlohmann::json& extra) {
  decode::CaptureDecodeResult decoded = decode::DecodeCaptureFile(capture, options);
  DecodeStageResult result;
  result.bundle.light_field = std::move(decoded.light_field);
  result.summary = std::move(decoded.summary);
  LightField& light_field = result.bundle.light_field;
  Stopwatch step;
  RoundToStoredPrecision(light_field, CompactBundleOptions(light_field).storage);
  result.summary["seconds"]["round_to_storage"] = step.Lap();
  if (out.empty()) return result;

  SaveLightField(result.bundle, out, bit_depth);
  result.summary["output"] = out.string();
  result.summary["seconds"]["write"] = step.Lap();
  result.summary["resident_mb"]["write"] = ResidentMegabytes();
  result.summary["peak_resident_mb"]["write"] = PeakResidentMegabytes();
  if (extra.is_object()) result.summary.update(extra);
  WriteJsonSummary(result.summary, SummaryPathFor(out));
  return result;
}

}  // namespace lfsp::stages
