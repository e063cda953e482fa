#include "lfsp/calibrate/calibration_io.h"

#include <Eigen/LU>
#include <cmath>
#include <fstream>
#include <sstream>

#include "lfsp/calibrate/lftoolbox_calibration.h"
#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/input_limits.h"
#include "lfsp/core/untrusted_json.h"

namespace lfsp::calibrate {
namespace {

using nlohmann::json;

json ViewsToJson(const std::vector<ViewIndex>& views) {
  json out = json::array();
  for (const auto& v : views) out.push_back({v.u, v.v});
  return out;
}

const json& Field(const json& object, const std::string& key, const std::string& source) {
  if (!object.is_object() || !object.contains(key))
    throw Error(source + ": calibration field '" + key + "' is missing");
  return object.at(key);
}

double Number(const json& object, const std::string& key, const std::string& source) {
  const json& value = Field(object, key, source);
  if (!value.is_number() || !std::isfinite(value.get<double>()))
    throw Error(source + ": calibration field '" + key + "' must be a finite number");
  return value.get<double>();
}

int Integer(const json& object, const std::string& key, const std::string& source, int min_value) {
  const json& value = Field(object, key, source);
  if (!value.is_number_integer() || value.get<long long>() < min_value || value.get<long long>() > 1000000)
    throw Error(source + ": calibration field '" + key + "' must be an integer >= " + std::to_string(min_value));
  return value.get<int>();
}

}  // namespace

json MatrixToJson(const Matrix5d& H) {
  json rows = json::array();
  for (int r = 0; r < 5; ++r) {
    json row = json::array();
    for (int c = 0; c < 5; ++c) row.push_back(H(r, c));
    rows.push_back(row);
  }
  return rows;
}

json CalibrationToJson(const Calibration& c) {
  json captures = json::array();
  for (const auto& p : c.captures) {
    captures.push_back({{"name", p.name},
                        {"rotation", p.rotation},
                        {"translation_m", p.translation},
                        {"rms_mm", p.rms_mm},
                        {"observations", p.observations},
                        {"views_used", ViewsToJson(p.views)},
                        {"dark_views", ViewsToJson(p.dark_views)},
                        {"edge_views", ViewsToJson(p.edge_views)},
                        {"failed_views", ViewsToJson(p.failed_views)}});
  }
  json stages = json::array();
  for (const auto& s : c.stages)
    stages.push_back({{"name", s.name},
                      {"rms_mm", s.rms_mm},
                      {"iterations", s.iterations},
                      {"observations", s.observations},
                      {"seconds", s.seconds}});
  json camera = {{"model", c.camera_model}, {"serial", c.serial}};
  camera["zoom_step"] = c.zoom_step ? json(*c.zoom_step) : json(nullptr);
  camera["focus_step"] = c.focus_step ? json(*c.focus_step) : json(nullptr);
  const Distortion& d = c.model.distortion;
  return {
      {"format", "lfsp-calibration"},
      {"version", 1},
      {"model", "Dansereau-Pizarro-Williams 2013 lenslet ray model"},
      {"index_convention",
       "n = (i, j, k, l, 1), 0-based: i = pixel column x, j = pixel row y, k = view column u, l = view row v; "
       "ray (s, t, u, v, 1) = H n in metres, relative two-plane parameterisation with 1 m plane separation"},
      {"light_field", {{"nu", c.shape.nu}, {"nv", c.shape.nv}, {"width", c.shape.width}, {"height", c.shape.height}}},
      {"H", MatrixToJson(c.model.H)},
      {"distortion", {{"k1", d.k1}, {"k2", d.k2}, {"k3", d.k3}, {"b1", d.b1}, {"b2", d.b2}}},
      {"checkerboard", {{"corners", {c.corners_x, c.corners_y}}, {"square_size_m", c.square_size}}},
      {"camera", camera},
      {"rms_mm", c.rms_mm},
      {"captures", captures},
      {"rejected_captures", c.rejected_captures},
      {"stages", stages},
      {"warnings", c.warnings}};
}

Matrix5d MatrixFromJson(const json& rows, const std::string& field, const std::string& source) {
  if (!rows.is_array() || rows.size() != 5)
    throw Error(source + ": calibration field '" + field + "' must be 5 rows of 5 numbers");
  Matrix5d H;
  for (int r = 0; r < 5; ++r) {
    const json& row = rows[static_cast<std::size_t>(r)];
    if (!row.is_array() || row.size() != 5)
      throw Error(source + ": calibration field '" + field + "' must be 5 rows of 5 numbers");
    for (int col = 0; col < 5; ++col) {
      const json& v = row[static_cast<std::size_t>(col)];
      if (!v.is_number() || !std::isfinite(v.get<double>()))
        throw Error(source + ": calibration field '" + field + "' holds a non-number at row " + std::to_string(r + 1));
      H(r, col) = v.get<double>();
    }
  }
  const double determinant = H.determinant();
  if (!std::isfinite(determinant) || std::abs(determinant) < 1e-40 || !H.inverse().allFinite())
    throw Error(source + ": calibration matrix '" + field + "' is singular or too extreme to invert");
  return H;
}

namespace {

Calibration ParseCalibration(const json& j, const std::string& source) {
  if (!j.is_object() || !j.contains("format") || j["format"] != "lfsp-calibration")
    throw Error(source + ": not an lfsp calibration file (field 'format' must be \"lfsp-calibration\")");
  Calibration c;
  const json& lf = Field(j, "light_field", source);
  c.shape.nu = Integer(lf, "nu", source, 1);
  c.shape.nv = Integer(lf, "nv", source, 1);
  c.shape.width = Integer(lf, "width", source, 1);
  c.shape.height = Integer(lf, "height", source, 1);
  c.shape.channels = 1;
  c.model.H = MatrixFromJson(Field(j, "H", source), "H", source);
  const json& d = Field(j, "distortion", source);
  c.model.distortion = {Number(d, "k1", source), Number(d, "k2", source), Number(d, "k3", source),
                        Number(d, "b1", source), Number(d, "b2", source)};
  if (j.contains("checkerboard") && j["checkerboard"].is_object()) {
    const json& board = j["checkerboard"];
    if (board.contains("corners") && board["corners"].is_array() && board["corners"].size() == 2) {
      c.corners_x = board["corners"][0].get<int>();
      c.corners_y = board["corners"][1].get<int>();
    }
    if (board.contains("square_size_m") && board["square_size_m"].is_number())
      c.square_size = board["square_size_m"].get<double>();
  }
  if (j.contains("rms_mm") && j["rms_mm"].is_number()) c.rms_mm = j["rms_mm"].get<double>();
  return c;
}

}  // namespace

Calibration CalibrationFromJson(const json& j, const std::string& source) {
  try {
    if (IsLfToolboxCalibration(j)) return CalibrationFromLfToolbox(j, source);
    return ParseCalibration(j, source);
  } catch (const json::exception& e) {  // a field of the wrong type
    throw Error(source + ": malformed calibration: " + e.what());
  }
}

void WriteCalibration(const Calibration& calibration, const std::filesystem::path& path) {
  AtomicOutput output(path);
  {
    std::ofstream file(output.temporary());
    if (!file) ThrowFileError(path.string(), "cannot write");
    file << CalibrationToJson(calibration).dump(2) << '\n';
    if (!file) ThrowFileError(path.string(), "write failed");
  }
  output.Commit();
}

Calibration ReadCalibration(const std::filesystem::path& path) {
  return CalibrationFromJson(ParseUntrustedJson(ReadWholeFile(path), path.string()), path.string());
}

}  // namespace lfsp::calibrate
