#pragma once

#include <cstdint>

namespace lfsp::segment {

// Makes every label of one view's label map (width x height, row-major) 4-connected: each label keeps its largest
// connected piece, and every other piece joins the label it shares most of its border with among the regions that
// are already settled (a label's largest piece, or a piece that joined one), so no piece is left as an island of
// the label it joined. Ties go to the smaller label. Returns the number of rays relabelled.
long long KeepLargestPieces(std::int32_t* labels, int width, int height);

}  // namespace lfsp::segment
