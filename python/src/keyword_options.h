#pragma once

#include <pybind11/pybind11.h>

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace lfsp::python {
namespace py = pybind11;

// Adds a command's options to a CLI11 app: the same functions `lfsp` builds its commands with (apps/arguments),
// so every keyword has the command line's name (`lambda_p` for --lambda-p), default, checks and help.
using OptionAdder = std::function<void(CLI::App*)>;

// Parses Python keywords as the command line parses the same options: k=v becomes `--k v` (underscores as
// dashes), True a bare flag, False and None nothing (the default), a list or tuple one `--k item` per item.
// TypeError for a keyword the function does not take (as Python says it); lfsp::Error, in the command line's words
// but naming keywords, for a value the option refuses.
void ParseKeywords(const std::string& function, const py::kwargs& keywords, const OptionAdder& add_options);

// True when one of `keywords` is an option `add_options` adds.
bool AnyKeywordOf(const py::kwargs& keywords, const OptionAdder& add_options);

// The options as a docstring section: each keyword with its type, default and the command line's help text.
std::string KeywordHelp(const OptionAdder& add_options);

}  // namespace lfsp::python
