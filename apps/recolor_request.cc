#include "recolor_request.h"

#include <charconv>
#include <system_error>

#include "input_loading.h"
#include "lfsp/core/error.h"
#include "lfsp/core/view_crop.h"
#include "view_selection.h"

namespace lfsp::cli {
namespace {

// The shortest text that parses back to exactly `value`.
std::string ExactNumber(float value) {
  char buffer[32];
  const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string JoinedIds(const std::vector<std::int32_t>& ids) {
  std::string text;
  for (const std::int32_t id : ids) text += (text.empty() ? "" : ",") + std::to_string(id);
  return text;
}

}  // namespace

edit::RecolorOptions RecolorOptionsOf(const RecolorRequest& request) {
  if (request.bit_depth != 8 && request.bit_depth != 16) throw Error("--bit-depth: expected 8 or 16");
  return ToRecolorOptions(request.colour_edit);
}

void AttachLabels(Bundle& bundle, const RecolorRequest& request, nlohmann::ordered_json& summary) {
  if (!request.labels.empty()) {
    bundle.labels = ReadLabels(request.labels);
  } else if (!bundle.labels) {
    throw Error(request.input + ": holds no labels; give --labels LABELS.h5 (as `lfsp segment` writes it)");
  }
  // Labels made on the well-lit central views (as `lfsp segment` chooses them) select the same views here.
  const int requested = ViewsForLabels(request.views, bundle.light_field.shape(), bundle.labels->shape());
  summary["views"] = SelectViews(bundle, requested, request.input);
  summary["labels"] = request.labels.empty() ? request.input : request.labels;
  RequireLabelsMatch(*bundle.labels, bundle.light_field.shape(), summary["labels"].get<std::string>());
}

Bundle LoadLabelledInput(const RecolorRequest& request, nlohmann::ordered_json& summary) {
  Bundle bundle = LoadInput(request.input);
  AttachLabels(bundle, request, summary);
  return bundle;
}

std::vector<std::string> RecolorCommandLine(const RecolorRequest& request) {
  std::vector<std::string> arguments = {"recolor", request.input};
  if (!request.labels.empty()) arguments.insert(arguments.end(), {"--labels", request.labels});
  if (request.views > 0) arguments.insert(arguments.end(), {"--views", std::to_string(request.views)});
  const RecolorArguments& edit = request.colour_edit;
  arguments.insert(arguments.end(), {"--label-ids", JoinedIds(request.label_ids), "--hue", ExactNumber(edit.hue),
                                     "--saturation", ExactNumber(edit.saturation), "--value", ExactNumber(edit.value),
                                     "--space", edit.space, "--feather", ExactNumber(edit.feather)});
  if (edit.no_weights) arguments.push_back("--no-weights");
  if (request.bit_depth != 8) arguments.insert(arguments.end(), {"--bit-depth", std::to_string(request.bit_depth)});
  arguments.insert(arguments.end(), {"--out", request.out});
  return arguments;
}

}  // namespace lfsp::cli
