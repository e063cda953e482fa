#pragma once

#include <opencv2/core/mat.hpp>
#include <string>

#include "lfsp/core/light_field.h"

namespace lfsp::edit {

// Where hue, saturation and value are changed.
enum class ColourSpace {
  kLch,  // CIE L*C*h (from CIELab through OpenCV): hue rotates (a*, b*), saturation scales chroma, value scales L*
  kHsv,  // HSV on the stored values: hue rotates H, saturation scales S, value scales V
};

std::string ToString(ColourSpace space);
ColourSpace ColourSpaceFromString(const std::string& name);  // "lch" or "hsv"; throws lfsp::Error otherwise

struct ColourAdjustment {
  float hue_degrees = 0.0f;  // rotation of the hue angle
  float saturation = 1.0f;   // factor, >= 0
  float value = 1.0f;        // factor, >= 0
  ColourSpace space = ColourSpace::kLch;

  bool IsIdentity() const { return hue_degrees == 0.0f && saturation == 1.0f && value == 1.0f; }
};

// Throws lfsp::Error naming the option if a factor is negative or anything is not finite.
void ValidateAdjustment(const ColourAdjustment& adjustment);

// Adjusts RGB colours in place. `pixels` is CV_32FC3 (any shape, continuous), RGB in [0, 1] in the given transfer
// encoding (OpenCV's CIELab conversion needs to know whether values are sRGB-encoded or linear). Results are
// clamped to [0, 1].
void AdjustColours(cv::Mat& pixels, const ColourAdjustment& adjustment, Transfer transfer);

}  // namespace lfsp::edit
