#pragma once

#include "lfsp/core/light_field.h"

namespace lfsp {

// The central n x n views of a light field (or of its labels), e.g. the 9x9 views a Lytro user keeps of a 15x15
// decode whose outer ring is dark with vignetting. The views keep their order; the centre view stays the centre.
// Throws lfsp::Error unless 1 <= n <= the smaller view count and n has the same parity as it (so a centre exists
// in both).
LightField CentralViews(const LightField& light_field, int n);
Labels CentralViews(const Labels& labels, int n);

}  // namespace lfsp
