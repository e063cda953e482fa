#include "recolor_spec.h"

#include <sstream>

#include "lfsp/core/error.h"
#include "lfsp/edit/selection.h"

namespace lfsp::pipeline {
namespace {

std::vector<std::string> Split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, separator))
    if (!part.empty()) parts.push_back(part);
  return parts;
}

double Number(const std::string& text, const std::string& key) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size()) return value;
  } catch (const std::exception&) {
  }
  throw Error("--recolor: " + key + "='" + text + "' is not a number");
}

// A non-negative label id; 1e20, nan and 3.5 are refused rather than cast.
int Integer(const std::string& text, const std::string& key) {
  try {
    std::size_t used = 0;
    const int value = std::stoi(text, &used);
    if (used == text.size() && value >= 0) return value;
  } catch (const std::exception&) {
  }
  throw Error("--recolor: " + key + "='" + text + "' is not a label id (an integer >= 0)");
}

}  // namespace

RecolorSpec ParseRecolorSpec(const std::string& text) {
  RecolorSpec spec;
  for (const std::string& pair : Split(text, ';')) {
    const auto equals = pair.find('=');
    if (equals == std::string::npos) throw Error("--recolor: '" + pair + "' is not key=value");
    const std::string key = pair.substr(0, equals);
    const std::string value = pair.substr(equals + 1);
    if (key == "at") {
      for (const std::string& point : Split(value, '+'))
        spec.points.push_back(edit::ParseViewPoint(point, "--recolor at"));
    } else if (key == "ids") {
      for (const std::string& id : Split(value, '+')) spec.ids.push_back(Integer(id, "ids"));
    } else if (key == "hue") {
      spec.options.adjustment.hue_degrees = static_cast<float>(Number(value, key));
    } else if (key == "saturation") {
      spec.options.adjustment.saturation = static_cast<float>(Number(value, key));
    } else if (key == "value") {
      spec.options.adjustment.value = static_cast<float>(Number(value, key));
    } else if (key == "feather") {
      spec.options.feather_px = static_cast<float>(Number(value, key));
    } else if (key == "space") {
      spec.options.adjustment.space = edit::ColourSpaceFromString(value);
    } else {
      throw Error("--recolor: unknown key '" + key + "' (expected at, ids, hue, saturation, value, feather, space)");
    }
  }
  if (spec.points.empty() && spec.ids.empty()) throw Error("--recolor: give at=x,y or ids=... to select superpixels");
  edit::ValidateAdjustment(spec.options.adjustment);
  return spec;
}

}  // namespace lfsp::pipeline
