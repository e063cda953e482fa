#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace lfsp {

// Where a JSON document came from, so that a lookup's lfsp::Error names the file and the field. Two documents
// name fields differently, and both keep their wording:
//   a metadata file (Lytro TXT/JSON, whites.json): "<file>: metadata field <path> is not a number";
//   an object inside a document (a scene):         "<where>.<path>: expected a number".
class JsonSource {
 public:
  // Implicit, so that a lookup can be given the file name as it is.
  JsonSource(std::string file) : name_(std::move(file)) {}
  JsonSource(const char* file) : name_(file) {}
  static JsonSource Object(std::string where);

  [[noreturn]] void WrongType(std::string_view path, const char* expected) const;  // expected: "a number"
  [[noreturn]] void Missing(std::string_view path) const;

 private:
  std::string name_;
  bool object_ = false;
};

// The value at a dotted path ("devices.lens.zoomStep"; "frames[0].frame" indexes an array), or nullptr if absent.
// A plain key is a one-step path.
const nlohmann::json* FindPath(const nlohmann::json& root, std::string_view path);

// Typed values at a dotted path. Absent or null -> nullopt (Lytro files write null for unknown values); present
// with another type -> lfsp::Error from `source`.
std::optional<double> NumberAt(const nlohmann::json& root, std::string_view path, const JsonSource& source);
std::optional<std::string> StringAt(const nlohmann::json& root, std::string_view path, const JsonSource& source);
// `value` as an int when it is a whole number an int holds, else nullopt (converting any other double to int is
// undefined behaviour).
std::optional<int> WholeInt(double value);

// A whole number that an int holds (a count, a step, a size); anything else present -> lfsp::Error "a whole number".
std::optional<int> IntAt(const nlohmann::json& root, std::string_view path, const JsonSource& source);
// Accepts the strings "true" and "false" too: some Lytro files write flags so.
std::optional<bool> BoolAt(const nlohmann::json& root, std::string_view path, const JsonSource& source);

// The same, but a missing value is an lfsp::Error too; it names the field as `prefix` + `path` (a caller that
// looks inside a sub-object passes the sub-object's path as prefix).
double RequireNumber(const nlohmann::json& root, std::string_view path, const JsonSource& source,
                     std::string_view prefix = "");
int RequireInt(const nlohmann::json& root, std::string_view path, const JsonSource& source,
               std::string_view prefix = "");
std::string RequireString(const nlohmann::json& root, std::string_view path, const JsonSource& source,
                          std::string_view prefix = "");

}  // namespace lfsp
