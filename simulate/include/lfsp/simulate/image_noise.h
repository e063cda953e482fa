#pragma once

#include <cstdint>

#include "lfsp/core/light_field.h"

namespace lfsp::simulate {

// Adds white Gaussian noise of standard deviation `sigma` (sample units) to every sample, then clamps to [0, 1], as
// an 8-bit-like image would hold it. The same seed gives the same noise. sigma <= 0 leaves the light field as it is.
void AddGaussianNoise(LightField& light_field, double sigma, std::uint64_t seed);

}  // namespace lfsp::simulate
