#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <optional>

#include "lfsp/core/light_field.h"
#include "lfsp/core/registration.h"

namespace lfsp::pipeline {

// A decoded capture against the ideal light field the simulator wrote beside it, for the report's panel: where the
// decode places each view (registration of every view whose mean weight is above kRegisteredWeight) and how far
// its centre view is from the truth (per pixel, in linear light, after one gain per channel: the exposure and the
// camera colour's white balance are not errors).
struct TruthComparison {
  static constexpr double kRegisteredWeight = 0.5;
  ViewRegistration registration;
  // The registration leaves out pixels this close to a depth edge of the truth (0: none left out), where the views
  // differ by what each occludes rather than by a shift.
  int depth_edge_margin_px = 0;
  int nu = 0, nv = 0;
  cv::Mat centre_error;  // CV_32FC1, mean over channels of |gain * decoded - truth|
  double centre_rms = 0.0;
  double centre_psnr_db = 0.0;
};
// The ideal light field is read from the bundle `truth` (of decoded's shape, or holding decoded's views as its central
// block) a row of views at a time: only a row of
// it is held beside the decoded light field (the whole of it, 1.2 GB in memory with its labels, made the pipeline's
// peak; issue 46).
TruthComparison CompareWithTruth(const LightField& decoded, const std::filesystem::path& truth,
                                 const std::optional<DisparityMap>& truth_disparity);

nlohmann::ordered_json ToJson(const TruthComparison& comparison);

// The panel's two pictures (8-bit RGB): the centre view's error, TURBO over 0 .. 0.05, and one cell per view
// coloured by its registration error, TURBO over 0 .. 0.1 px (black: not registered, too dim).
cv::Mat CentreErrorPicture(const TruthComparison& comparison);
cv::Mat RegistrationPicture(const TruthComparison& comparison);
constexpr float kErrorPictureTop = 0.05f;
constexpr float kRegistrationPictureTop = 0.1f;

}  // namespace lfsp::pipeline
