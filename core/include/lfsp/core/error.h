#pragma once

#include <stdexcept>
#include <string>

namespace lfsp {

// `text` with every byte that is not printable, valid UTF-8 (control characters, line breaks, stray bytes of a
// binary file) written as \xHH, so a message that quotes a file's bytes stays one line that a terminal, a log and
// Python (whose str must be valid UTF-8) can all show. An HDF5 file read as PFM quoted its magic "\x89HDF" raw.
std::string PrintableText(const std::string& text);

// Thrown for bad input: a file that is missing, truncated, of the wrong size or with garbage metadata, or an
// option out of range. The message names the file (or option), the field or offset, and what was expected.
// The CLI prints it as one line and exits with status 2. Any other exception is an internal failure (status 1).
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(PrintableText(message)) {}
};

// Builds "<path>: <problem>", the shape of every message about a file.
std::string FileMessage(const std::string& path, const std::string& problem);

[[noreturn]] void ThrowFileError(const std::string& path, const std::string& problem);

// Libraries know no command line: a message about an option names it by its API name (the field of the options
// struct, e.g. "views_pattern") through OptionName, and each front end says how its users spell it. By default the
// name is kept as it is (what a library or Python caller passes); the CLI installs a namer that gives
// "--views-pattern".
std::string OptionName(const std::string& api_name);
using OptionNamer = std::string (*)(const std::string& api_name);
void SetOptionNamer(OptionNamer namer);

}  // namespace lfsp
