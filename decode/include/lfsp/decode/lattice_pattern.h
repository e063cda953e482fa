#pragma once

#include "lfsp/core/light_field.h"

namespace lfsp::decode {

// How strongly the lens lattice still shows in a decoded light field: the spectral energy of the centre view (grey,
// Hann-windowed) on the row of vertical frequency 1/2 cycle per row, divided by the mean energy per row of the band
// just below it (0.40..0.47 cycles per row). Shifted and unshifted lens rows that disagree (a wrong grid, white
// image or row shift) alternate row by row and put a spike there; a natural image's spectrum is smooth, so an ideal
// light field reads about 1 and a correct decode 1..3 (hexagonal sampling leaves a little), while a wrong row shift
// reads above 20 (measured on the simulator's captures, tests/decode/decode_test.cc).
double RowAlternationRatio(const LightField& light_field);

}  // namespace lfsp::decode
