#include "lfsp/calibrate/lftoolbox_calibration.h"

#include <cmath>

#include "lfsp/calibrate/calibration_io.h"
#include "lfsp/core/error.h"
#include "lfsp/core/json_fields.h"

namespace lfsp::calibrate {
namespace {

using nlohmann::json;

// Takes our 0-based (pixel column, pixel row, view column, view row, 1) to LFToolbox's 1-based (view column, view
// row, pixel column, pixel row, 1).
Matrix5d OurIndexToLfToolbox() {
  Matrix5d P = Matrix5d::Zero();
  P(0, 2) = 1.0;                  // view column
  P(1, 3) = 1.0;                  // view row
  P(2, 0) = 1.0;                  // pixel column
  P(3, 1) = 1.0;                  // pixel row
  P.block<4, 1>(0, 4).setOnes();  // 1-based
  P(4, 4) = 1.0;
  return P;
}

Distortion DistortionFrom(const json& calinfo, const std::string& source) {
  if (!calinfo.contains("EstCamDistortionV")) return {};  // LFToolbox's no-distortion phase writes none
  const json& d = calinfo["EstCamDistortionV"];
  if (!d.is_array() || d.size() != 5)
    throw Error(source + ": calibration field 'EstCamDistortionV' must be 5 numbers [k1 k2 k3 b1 b2]");
  std::array<double, 5> values{};
  for (std::size_t n = 0; n < 5; ++n) {
    if (!d[n].is_number() || !std::isfinite(d[n].get<double>()))
      throw Error(source + ": calibration field 'EstCamDistortionV' holds a non-number");
    values[n] = d[n].get<double>();
  }
  return Distortion::FromArray(values);
}

// CalOptions.LFSize: [views down, views across, pixel rows, pixel columns, channels] (LFToolbox's LF(j, i, l, k, c)).
LightFieldShape ShapeFrom(const json& calinfo, const std::string& source) {
  const json* size = FindPath(calinfo, "CalOptions.LFSize");
  if (!size || !size->is_array() || size->size() < 4)
    throw Error(source +
                ": calibration field 'CalOptions.LFSize' must list the light field's size "
                "[views down, views across, pixel rows, pixel columns, channels]");
  LightFieldShape shape;
  int* targets[4] = {&shape.nv, &shape.nu, &shape.height, &shape.width};
  for (std::size_t n = 0; n < 4; ++n) {
    const std::optional<int> value = (*size)[n].is_number() ? WholeInt((*size)[n].get<double>()) : std::nullopt;
    if (!value || *value < 1 || *value > 100000)
      throw Error(source + ": calibration field 'CalOptions.LFSize' holds a size that is not a positive whole number");
    *targets[n] = *value;
  }
  shape.channels = 1;
  return shape;
}

}  // namespace

bool IsLfToolboxCalibration(const json& json) { return json.is_object() && json.contains("EstCamIntrinsicsH"); }

Calibration CalibrationFromLfToolbox(const json& calinfo, const std::string& source) {
  const JsonSource where(source);
  Calibration c;
  c.model.H = MatrixFromJson(calinfo.at("EstCamIntrinsicsH"), "EstCamIntrinsicsH", source) * OurIndexToLfToolbox();
  c.model.distortion = DistortionFrom(calinfo, source);
  c.shape = ShapeFrom(calinfo, source);
  c.camera_model = StringAt(calinfo, "CamInfo.CamModel", where).value_or("");
  c.serial = StringAt(calinfo, "CamInfo.CamSerial", where).value_or("");
  c.zoom_step = IntAt(calinfo, "CamInfo.ZoomStep", where);
  c.focus_step = IntAt(calinfo, "CamInfo.FocusStep", where);
  const std::string version = StringAt(calinfo, "GeneratedByInfo.VersionStr", where).value_or("unknown version");
  c.warnings.push_back("imported from LFToolbox's " + source + " (" + version +
                       "): intrinsics and distortion only; its poses, board and errors are not carried over");
  return c;
}

}  // namespace lfsp::calibrate
