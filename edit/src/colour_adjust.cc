#include "lfsp/edit/colour_adjust.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "lfsp/core/error.h"

namespace lfsp::edit {

std::string ToString(ColourSpace space) { return space == ColourSpace::kLch ? "lch" : "hsv"; }

ColourSpace ColourSpaceFromString(const std::string& name) {
  if (name == "lch") return ColourSpace::kLch;
  if (name == "hsv") return ColourSpace::kHsv;
  throw Error("colour space '" + name + "' is unknown (expected lch or hsv)");
}

void ValidateAdjustment(const ColourAdjustment& adjustment) {
  if (!std::isfinite(adjustment.hue_degrees))
    throw Error(OptionName("hue") + ": expected a finite angle in degrees, got " +
                std::to_string(adjustment.hue_degrees));
  if (!(adjustment.saturation >= 0.0f) || !std::isfinite(adjustment.saturation))
    throw Error(OptionName("saturation") + ": expected a finite factor >= 0, got " +
                std::to_string(adjustment.saturation));
  if (!(adjustment.value >= 0.0f) || !std::isfinite(adjustment.value))
    throw Error(OptionName("value") + ": expected a finite factor >= 0, got " + std::to_string(adjustment.value));
}

namespace {

// Hue rotation and chroma scaling in the (a*, b*) plane, lightness scaling, in CIELab.
void AdjustLab(cv::Mat& lab, const ColourAdjustment& adjustment) {
  const float angle = adjustment.hue_degrees * std::numbers::pi_v<float> / 180.0f;
  const float cos_scaled = std::cos(angle) * adjustment.saturation;
  const float sin_scaled = std::sin(angle) * adjustment.saturation;
  float* values = lab.ptr<float>(0);
  const std::size_t count = lab.total();
  for (std::size_t i = 0; i < count; ++i) {
    float* p = values + 3 * i;
    const float a = p[1];
    const float b = p[2];
    p[0] = std::min(100.0f, p[0] * adjustment.value);
    p[1] = cos_scaled * a - sin_scaled * b;
    p[2] = sin_scaled * a + cos_scaled * b;
  }
}

void AdjustHsv(cv::Mat& hsv, const ColourAdjustment& adjustment) {
  float* values = hsv.ptr<float>(0);
  const std::size_t count = hsv.total();
  const float hue_shift = std::fmod(adjustment.hue_degrees, 360.0f);
  for (std::size_t i = 0; i < count; ++i) {
    float* p = values + 3 * i;
    float hue = std::fmod(p[0] + hue_shift, 360.0f);
    if (hue < 0.0f) hue += 360.0f;
    p[0] = hue;
    p[1] = std::min(1.0f, p[1] * adjustment.saturation);
    p[2] = std::min(1.0f, p[2] * adjustment.value);
  }
}

}  // namespace

void AdjustColours(cv::Mat& pixels, const ColourAdjustment& adjustment, Transfer transfer) {
  if (pixels.type() != CV_32FC3 || !pixels.isContinuous())
    throw Error("colour adjustment: expected a continuous CV_32FC3 RGB image");
  ValidateAdjustment(adjustment);
  if (pixels.empty() || adjustment.IsIdentity()) return;
  cv::Mat converted;
  if (adjustment.space == ColourSpace::kLch) {
    // OpenCV's RGB2Lab applies the sRGB decoding curve itself; LRGB2Lab takes linear values.
    const bool srgb = transfer == Transfer::kSrgb;
    cv::cvtColor(pixels, converted, srgb ? cv::COLOR_RGB2Lab : cv::COLOR_LRGB2Lab);
    AdjustLab(converted, adjustment);
    cv::cvtColor(converted, pixels, srgb ? cv::COLOR_Lab2RGB : cv::COLOR_Lab2LRGB);
  } else {
    cv::cvtColor(pixels, converted, cv::COLOR_RGB2HSV);
    AdjustHsv(converted, adjustment);
    cv::cvtColor(converted, pixels, cv::COLOR_HSV2RGB);
  }
  float* values = pixels.ptr<float>(0);
  const std::size_t count = pixels.total() * 3;
  for (std::size_t i = 0; i < count; ++i) values[i] = std::min(1.0f, std::max(0.0f, values[i]));
}

}  // namespace lfsp::edit
