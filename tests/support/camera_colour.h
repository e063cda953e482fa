#pragma once

#include <string>

#include "lfsp/core/light_field.h"

namespace lfsp::testing {

// Issue 12's colour criterion, as EXPECTs: the centre view of a camera-colour decode (sRGB, taken back to linear),
// over the ideal light field's centre view, per channel; the three ratios agree to 5 % of their mean, and under
// `max_clipped` (1 %) of the decode's samples are clipped at black. Prints the ratios and the clipped share, labelled
// `what`.
void CheckCameraColour(const LightField& camera, const LightField& truth, const std::string& what,
                       double max_clipped = 0.01);

}  // namespace lfsp::testing
