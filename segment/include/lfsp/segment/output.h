#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/segment/plane.h"

namespace lfsp::segment {

// Writes one 16-bit PNG per view, `folder`/label_Cam%03d.png (cam = v * nu + u), holding the label of every pixel
// (65535 for an unlabelled ray). Throws lfsp::Error if a label does not fit in 16 bits. The folder is created;
// each file is written under a temporary name and renamed.
void WriteLabelPngs(const Labels& labels, const std::filesystem::path& folder);

// The centre view (8-bit RGB) with superpixel boundaries drawn in red.
cv::Mat CentreOverlay(const LightField& light_field, const Labels& labels);

// Epipolar-plane images with label boundaries in red: horizontal = the centre row of views (v = vc) at image row
// `y`, one image row per view; vertical = the centre column of views at image column `x`. Each view's line is
// repeated `scale` times so the EPI is readable. Returned as 8-bit BGR (ready for PNG).
cv::Mat HorizontalEpiOverlay(const LightField& light_field, const Labels& labels, int y, int scale = 8);
cv::Mat VerticalEpiOverlay(const LightField& light_field, const Labels& labels, int x, int scale = 8);

// Writes an 8-bit image as PNG through a temporary file.
void WritePng(const cv::Mat& image, const std::filesystem::path& path);

// Planes as JSON: [{"label": k, "a": .., "b": .., "c": ..}], d(x, y) = a x + b y + c in centre-view pixels.
nlohmann::json PlanesToJson(const std::vector<Plane>& planes);

}  // namespace lfsp::segment
