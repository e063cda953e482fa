#pragma once

#include <functional>
#include <optional>
#include <string>

#include "lfsp/core/light_field.h"

namespace lfsp {

// The central n x n views of a light field (or of its labels), e.g. the 9x9 views a Lytro user keeps of a 15x15
// decode whose outer ring is dark with vignetting. The views keep their order; the centre view stays the centre.
// Throws lfsp::Error unless 1 <= n <= the smaller view count and n has the same parity as it (so a centre exists
// in both).
LightField CentralViews(const LightField& light_field, int n);
// The shape of those views (the same lfsp::Error when they cannot be taken).
LightFieldShape CentralShape(const LightFieldShape& shape, int n);
Labels CentralViews(const Labels& labels, int n);

// Where those views lie: the block of the central n x n views of a light field of the shape `shape` (same checks).
ViewBlock CentralViewBlock(const LightFieldShape& shape, int n);

// Views are well lit when their mean weight (a lenslet decode's vignetting) is at least this: beyond it, the rays
// sample the soft edge of the micro-images, where noise is amplified and the neighbouring micro-image is near.
// It keeps the central 9x9 of an Illum decode (the next ring's dimmest view: 0.37) and 7x7 of an F01 (its dimmest
// view 0.48); on noisy full-size F01 strips, 7x7 puts every strip's disparity within 0.012 px, 5x5 within 0.04.
constexpr double kWellLitWeight = 0.4;

// The mean weight of one view (the light field must have weights).
double MeanViewWeight(const LightField& light_field, ViewIndex view);
// The mean of `count` weights, summed in order in double: how every view's mean weight is taken, wherever the
// weights come from (a light field, or a bundle read a row of views at a time: ReadViewMeanWeights).
double MeanOfWeights(const float* weights, std::size_t count);

// The rule ChooseViews applies, on any source of the views' mean weights: the side of the largest central square
// of views (of the parity of the smaller view count) whose every view has a mean weight of at least `threshold`.
// Ring by ring from the centre, so only the rings it reaches are asked for.
int WellLitCentralSize(const LightFieldShape& shape, const std::function<double(ViewIndex)>& mean_weight,
                       double threshold = kWellLitWeight);

// The views a stage should process: the central n x n, n the largest size of the light field's parity whose every
// view is well lit (all views when the light field has no weights), or `requested` when it is > 0 (lfsp::Error if
// it cannot be taken). `reason` says which, for logs and summaries.
struct ViewChoice {
  int n = 0;
  int available = 0;
  double least_weight = 1.0;  // the lowest mean weight among the chosen views (1 without weights)
  std::string reason;
};
ViewChoice ChooseViews(const LightField& light_field, int requested = 0);
// The same for a light field of the shape `shape` whose views' mean weights `mean_weight` gives (empty: it has no
// weights), so that the views can be chosen before the samples are read (LoadCentralViews).
ViewChoice ChooseViews(const LightFieldShape& shape, const std::function<double(ViewIndex)>& mean_weight,
                       int requested = 0);

// The views to request (for ChooseViews) when working with labels made on the well-lit central views (as segment
// chooses them): `requested` when > 0, else the labels' view count when they have fewer views than the light field,
// else 0 (ChooseViews decides). Used by recolor, the viewer's export and Python.
int ViewsForLabels(int requested, const LightFieldShape& light_field, const LightFieldShape& labels);

// Keeps the central n x n views of a light field and of its labels in place (nothing is copied when n is already
// the view count).
void KeepCentralViews(LightField& light_field, std::optional<Labels>& labels, int n);

// ChooseViews, then KeepCentralViews of the choice: what a stage does with a light field it has read whole.
ViewChoice KeepChosenViews(LightField& light_field, std::optional<Labels>& labels, int requested = 0);

}  // namespace lfsp
