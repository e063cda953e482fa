#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <string>

#include "lfsp/core/error.h"

// Small checked accessors for the scene JSON: every failure names the field path (`where.key`).
namespace lfsp::simulate {

inline std::string RequireString(const nlohmann::json& json, const char* key, const std::string& where) {
  if (!json.contains(key) || !json.at(key).is_string()) throw Error(where + "." + key + ": expected a string");
  return json.at(key).get<std::string>();
}

inline float ReadFloat(const nlohmann::json& json, const char* key, float fallback, const std::string& where) {
  if (!json.contains(key)) return fallback;
  if (!json.at(key).is_number()) throw Error(where + "." + key + ": expected a number");
  return json.at(key).get<float>();
}

inline std::array<float, 2> ReadPoint(const nlohmann::json& json, const std::string& where) {
  if (!json.is_array() || json.size() != 2 || !json[0].is_number() || !json[1].is_number())
    throw Error(where + ": expected [x, y]");
  return {json[0].get<float>(), json[1].get<float>()};
}

inline std::array<float, 2> ReadPoint(const nlohmann::json& json, const char* key, std::array<float, 2> fallback,
                                      const std::string& where) {
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
