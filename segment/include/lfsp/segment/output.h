#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/segment/plane.h"

namespace lfsp::segment {

// Writes one 16-bit PNG per view, `folder`/label_Cam%03d.png (cam = v * nu + u), holding the label of every pixel
// (65535 for an unlabelled ray). Throws lfsp::Error if a label does not fit in 16 bits. The folder is created;
// each file is written under a temporary name and renamed. (Boundary pictures: core/visualize.h.)
void WriteLabelPngs(const Labels& labels, const std::filesystem::path& folder);

// Planes as JSON: [{"label": k, "a": .., "b": .., "c": ..}], d(x, y) = a x + b y + c in centre-view pixels.
nlohmann::json PlanesToJson(const std::vector<Plane>& planes);

}  // namespace lfsp::segment
