#pragma once

#include <string>
#include <vector>

namespace lfsp::cli {

// The arguments as one line a POSIX shell reads back into them (single quotes where needed), for the command lines
// lfsp prints for its users to run.
std::string ShellQuoted(const std::vector<std::string>& arguments);

}  // namespace lfsp::cli
