#pragma once

#include <filesystem>
#include <string>

namespace lfsp {

// A path's extension in lower case (".PNG" -> ".png"): how every reader and writer picks a format by name.
std::string LowerExtension(const std::filesystem::path& path);

}  // namespace lfsp
