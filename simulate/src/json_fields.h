#pragma once

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "lfsp/core/error.h"
#include "lfsp/core/json_fields.h"

// Small checked accessors for the scene JSON: every failure names the field path (`where.key`). Typed lookups are
// core's (lfsp/core/json_fields.h); what is added here is the scene's own checks (objects, ranges, points, colours).
namespace lfsp::simulate {

inline std::string RequireString(const nlohmann::json& json, const char* key, const std::string& where) {
  if (!json.is_object()) throw Error(where + ": expected an object");
  return lfsp::RequireString(json, key, JsonSource::Object(where));
}

// Every number in a scene is a coordinate, size, disparity or angle: anything beyond +-1e4 (or not finite) is a
// mistake, and rejecting it keeps the renderer's arithmetic finite.
constexpr double kMaxSceneNumber = 1e4;

inline float CheckedNumber(const nlohmann::json& value, const std::string& where) {
  if (!value.is_number()) throw Error(where + ": expected a number");
  const double v = value.get<double>();
  if (!std::isfinite(v) || std::abs(v) > kMaxSceneNumber)
    throw Error(where + ": number out of range (|value| must be <= 1e4)");
  return static_cast<float>(v);
}

inline float ReadFloat(const nlohmann::json& json, const char* key, float fallback, const std::string& where) {
  if (!json.is_object()) throw Error(where + ": expected an object");
  if (!json.contains(key)) return fallback;
  return CheckedNumber(json.at(key), where + "." + key);
}

inline std::array<float, 2> ReadPoint(const nlohmann::json& json, const std::string& where) {
  if (!json.is_array() || json.size() != 2 || !json[0].is_number() || !json[1].is_number())
    throw Error(where + ": expected [x, y]");
  return {CheckedNumber(json[0], where + "[0]"), CheckedNumber(json[1], where + "[1]")};
}

inline std::array<float, 2> ReadPoint(const nlohmann::json& json, const char* key, std::array<float, 2> fallback,
                                      const std::string& where) {
  if (!json.is_object()) throw Error(where + ": expected an object");
  if (!json.contains(key)) return fallback;
  return ReadPoint(json.at(key), where + "." + key);
}

inline std::array<float, 3> ReadRgb(const nlohmann::json& json, const std::string& where) {
  if (!json.is_array() || json.size() != 3) throw Error(where + ": expected [r, g, b] in [0, 1]");
  std::array<float, 3> rgb{};
  for (int c = 0; c < 3; ++c) {
    if (!json[c].is_number()) throw Error(where + ": expected [r, g, b] in [0, 1]");
    rgb[c] = json[c].get<float>();
    if (rgb[c] < 0.0f || rgb[c] > 1.0f) throw Error(where + ": colour components must be in [0, 1]");
  }
  return rgb;
}

}  // namespace lfsp::simulate
