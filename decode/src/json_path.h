#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace lfsp::decode {

// Small typed lookups into Lytro metadata by dotted path
// ("devices.lens.zoomStep"; "frames[0].frame" indexes an array). Absent ->
// nullptr / nullopt; present with the wrong type -> lfsp::Error naming `source`
// and the path.
const nlohmann::json* FindPath(const nlohmann::json& root, std::string_view path);
std::optional<double> NumberAt(const nlohmann::json& root, std::string_view path, const std::string& source);
std::optional<std::string> StringAt(const nlohmann::json& root, std::string_view path, const std::string& source);
std::optional<bool> BoolAt(const nlohmann::json& root, std::string_view path, const std::string& source);

// The same, but a missing value is an lfsp::Error "<source>: metadata field
// <prefix><path> is missing".
double RequireNumber(const nlohmann::json& root, std::string_view path, const std::string& source,
                     std::string_view prefix = "");
std::string RequireString(const nlohmann::json& root, std::string_view path, const std::string& source,
                          std::string_view prefix = "");

}  // namespace lfsp::decode
