#include "lfsp/core/json_fields.h"

#include <charconv>
#include <cmath>
#include <limits>

#include "lfsp/core/error.h"

namespace lfsp {
namespace {

// Steps into `node` by one path component "name" or "name[3]"; nullptr if absent.
const nlohmann::json* Step(const nlohmann::json* node, std::string_view component) {
  std::string_view name = component;
  std::optional<std::size_t> index;
  const std::size_t bracket = component.find('[');
  if (bracket != std::string_view::npos && component.back() == ']') {
    name = component.substr(0, bracket);
    const std::string_view digits = component.substr(bracket + 1, component.size() - bracket - 2);
    std::size_t value = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error != std::errc() || end != digits.data() + digits.size()) return nullptr;
    index = value;
  }
  if (!name.empty()) {
    if (!node->is_object()) return nullptr;
    const auto it = node->find(std::string(name));
    if (it == node->end()) return nullptr;
    node = &*it;
  }
  if (index) {
    if (!node->is_array() || *index >= node->size()) return nullptr;
    node = &(*node)[*index];
  }
  return node;
}

}  // namespace

JsonSource JsonSource::Object(std::string where) {
  JsonSource source(std::move(where));
  source.object_ = true;
  return source;
}

void JsonSource::WrongType(std::string_view path, const char* expected) const {
  if (object_) throw Error(name_ + "." + std::string(path) + ": expected " + expected);
  throw Error(name_ + ": metadata field " + std::string(path) + " is not " + expected);
}

void JsonSource::Missing(std::string_view path) const {
  if (object_) throw Error(name_ + "." + std::string(path) + ": missing");
  throw Error(name_ + ": metadata field " + std::string(path) + " is missing");
}

const nlohmann::json* FindPath(const nlohmann::json& root, std::string_view path) {
  const nlohmann::json* node = &root;
  while (node != nullptr && !path.empty()) {
    const std::size_t dot = path.find('.');
    node = Step(node, path.substr(0, dot));
    path = dot == std::string_view::npos ? std::string_view() : path.substr(dot + 1);
  }
  return node;
}

std::optional<double> NumberAt(const nlohmann::json& root, std::string_view path, const JsonSource& source) {
  const nlohmann::json* value = FindPath(root, path);
  if (value == nullptr || value->is_null()) return std::nullopt;
  if (!value->is_number()) source.WrongType(path, "a number");
  return value->get<double>();
}

std::optional<int> WholeInt(double value) {
  if (!(std::isfinite(value) && value == std::floor(value) && value >= std::numeric_limits<int>::min() &&
        value <= std::numeric_limits<int>::max()))
    return std::nullopt;
  return static_cast<int>(value);
}

std::optional<int> IntAt(const nlohmann::json& root, std::string_view path, const JsonSource& source) {
  const std::optional<double> value = NumberAt(root, path, source);
  if (!value) return std::nullopt;
  const std::optional<int> whole = WholeInt(*value);  // make fuzz found 7.9e15 in a whites.json
  if (!whole) source.WrongType(path, "a whole number");
  return whole;
}

std::optional<std::string> StringAt(const nlohmann::json& root, std::string_view path, const JsonSource& source) {
  const nlohmann::json* value = FindPath(root, path);
  if (value == nullptr || value->is_null()) return std::nullopt;
  if (!value->is_string()) source.WrongType(path, "a string");
  return value->get<std::string>();
}

std::optional<bool> BoolAt(const nlohmann::json& root, std::string_view path, const JsonSource& source) {
  const nlohmann::json* value = FindPath(root, path);
  if (value == nullptr || value->is_null()) return std::nullopt;
  if (value->is_boolean()) return value->get<bool>();
  if (value->is_string() && (*value == "true" || *value == "false")) return *value == "true";
  source.WrongType(path, "a boolean");
}

double RequireNumber(const nlohmann::json& root, std::string_view path, const JsonSource& source,
                     std::string_view prefix) {
  const std::optional<double> value = NumberAt(root, path, source);
  if (!value) source.Missing(std::string(prefix) + std::string(path));
  return *value;
}

int RequireInt(const nlohmann::json& root, std::string_view path, const JsonSource& source, std::string_view prefix) {
  const std::optional<int> value = IntAt(root, path, source);
  if (!value) source.Missing(std::string(prefix) + std::string(path));
  return *value;
}

std::string RequireString(const nlohmann::json& root, std::string_view path, const JsonSource& source,
                          std::string_view prefix) {
  std::optional<std::string> value = StringAt(root, path, source);
  if (!value) source.Missing(std::string(prefix) + std::string(path));
  return *std::move(value);
}

}  // namespace lfsp
