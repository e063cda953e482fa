#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace lfsp {

// Free-form metadata carried with a light field (HCI parameters.cfg sections, decoder facts, provenance).
// Keys are sections, values objects of scalars, e.g. meta["meta"]["disp_min"] = -3.3.
using Metadata = nlohmann::json;

struct DisparityRange {
  float min = 0.0f;
  float max = 0.0f;
};

// The disparity range recorded in the metadata (HCI: meta.disp_min / meta.disp_max), if any.
std::optional<DisparityRange> DisparityRangeFromMetadata(const Metadata& metadata);

void SetDisparityRange(Metadata& metadata, DisparityRange range);

}  // namespace lfsp
