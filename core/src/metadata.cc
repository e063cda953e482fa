#include "lfsp/core/metadata.h"

namespace lfsp {

std::optional<DisparityRange> DisparityRangeFromMetadata(const Metadata& metadata) {
  if (!metadata.is_object() || !metadata.contains("meta")) return std::nullopt;
  const Metadata& meta = metadata["meta"];
  if (!meta.is_object() || !meta.contains("disp_min") || !meta.contains("disp_max")) return std::nullopt;
  if (!meta["disp_min"].is_number() || !meta["disp_max"].is_number()) return std::nullopt;
  return DisparityRange{meta["disp_min"].get<float>(), meta["disp_max"].get<float>()};
}

void SetDisparityRange(Metadata& metadata, DisparityRange range) {
  if (!metadata.is_object()) metadata = Metadata::object();
  metadata["meta"]["disp_min"] = range.min;
  metadata["meta"]["disp_max"] = range.max;
}

}  // namespace lfsp
