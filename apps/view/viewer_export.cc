#include "view/viewer_export.h"

#include <fstream>
#include <opencv2/core.hpp>

#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"
#include "lfsp/edit/selection.h"
#include "shell_quoting.h"
#include "stages/recolor_stage.h"

namespace lfsp::view {
namespace fs = std::filesystem;

namespace {

template <typename T>
T Field(const nlohmann::json& edit, const char* name, T fallback) {
  if (!edit.contains(name)) return fallback;
  try {
    return edit.at(name).get<T>();
  } catch (const nlohmann::json::exception&) {
    throw Error(std::string("export: field '") + name + "' has the wrong type");
  }
}

cli::RecolorRequest RequestOf(const ViewerData& data, const nlohmann::json& edit, const fs::path& out) {
  if (!edit.is_object()) throw Error("export: expected a JSON object");
  cli::RecolorRequest request = data.recolor_base;
  request.label_ids = Field<std::vector<std::int32_t>>(edit, "label_ids", {});
  if (request.label_ids.empty()) throw Error("export: select at least one superpixel");
  request.colour_edit.hue = Field<float>(edit, "hue", 0.0f);
  request.colour_edit.saturation = Field<float>(edit, "saturation", 1.0f);
  request.colour_edit.value = Field<float>(edit, "value", 1.0f);
  request.colour_edit.space = Field<std::string>(edit, "space", "lch");
  request.colour_edit.feather = Field<float>(edit, "feather", 0.0f);
  request.out = out.string();
  return request;
}

// White where the centre view's ray carries a selected label.
cv::Mat CentreMask(const Labels& labels, const std::vector<std::int32_t>& selection) {
  const cv::Mat centre = labels.View(labels.shape().Centre());
  cv::Mat mask(centre.size(), CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < centre.rows; ++y)
    for (int x = 0; x < centre.cols; ++x)
      if (std::binary_search(selection.begin(), selection.end(), centre.at<std::int32_t>(y, x)))
        mask.at<std::uint8_t>(y, x) = 255;
  return mask;
}

}  // namespace

nlohmann::json ExportEdit(const ViewerData& data, const nlohmann::json& edit, const fs::path& folder) {
  if (!data.bundle.labels) throw Error("export: the light field has no labels (start lfsp view with --labels)");
  const fs::path out = folder / "recolored.h5";
  const cli::RecolorRequest request = RequestOf(data, edit, out);
  stages::RecolorStageOptions stage;
  stage.recolor = cli::RecolorOptionsOf(request);
  stage.bit_depth = request.bit_depth;
  stage.selection = edit::SelectLabelIds(*data.bundle.labels, request.label_ids);
  stage.how = {{"by", "label-ids"}, {"label_ids", request.label_ids}};

  fs::create_directories(folder);
  const std::vector<std::string> arguments = cli::RecolorCommandLine(request);
  const std::string command = "lfsp " + cli::ShellQuoted(arguments);
  Bundle edited = data.bundle;  // the page keeps showing the original
  stages::RunRecolorStage(edited, stage, out, {{"command", "recolor"}, {"input", request.input}, {"by", "lfsp view"}});

  const fs::path selection_json = folder / "selection.json";
  const fs::path selection_mask = folder / "selection_mask.png";
  WriteImage(CentreMask(*data.bundle.labels, stage.selection), selection_mask);
  std::ofstream file(selection_json);
  file << nlohmann::json{{"label_ids", stage.selection}, {"command", command}}.dump(2) << "\n";
  if (!file.flush()) ThrowFileError(selection_json.string(), "write failed");
  return {{"command", command},
          {"arguments", arguments},
          {"files", {out.string(), selection_json.string(), selection_mask.string()}}};
}

}  // namespace lfsp::view
