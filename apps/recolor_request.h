#pragma once

// What `lfsp recolor` is asked to do, whoever asks: the command's own options, or the viewer's export, which must
// write what the command writes and print the command line that does it.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "arguments/recolor_arguments.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/edit/recolor.h"

namespace lfsp::cli {

struct RecolorRequest {
  std::string input;   // the light field
  std::string labels;  // "" = the input's own
  int views = 0;       // central N x N; 0 = as many as the labels have (or chosen from the weights)
  std::vector<std::int32_t> label_ids;
  RecolorArguments colour_edit;  // hue, saturation, value, space, feather, no_weights
  int bit_depth = 8;
  std::string out;
};

// The library's options for the request's adjustment; throws lfsp::Error naming the option when one is invalid.
edit::RecolorOptions RecolorOptionsOf(const RecolorRequest& request);

// Gives `bundle` (the request's light field, as loaded) the labels to recolour by, the --labels file's else its
// own, and cuts both to the views the labels were made on, as `lfsp recolor` does. Records the views and labels
// chosen in `summary`. Throws lfsp::Error naming the input when it has no labels and none are given.
void AttachLabels(Bundle& bundle, const RecolorRequest& request, nlohmann::ordered_json& summary);

// The request's light field, loaded and given its labels (AttachLabels).
Bundle LoadLabelledInput(const RecolorRequest& request, nlohmann::ordered_json& summary);

// The arguments after `lfsp` that make `lfsp recolor` carry out the request by label ids: `recolor INPUT
// [--labels L] --label-ids 3,17 --hue ... --out OUT`. Numbers are written so they parse back to the same floats.
std::vector<std::string> RecolorCommandLine(const RecolorRequest& request);

}  // namespace lfsp::cli
