#include "keyword_options.h"

#include <memory>
#include <regex>
#include <vector>

#include "lfsp/core/error.h"

namespace lfsp::python {
namespace {

std::string FlagOf(const std::string& keyword) {
  std::string flag = "--" + keyword;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

std::string KeywordOf(const std::string& flag) {
  std::string keyword = flag.substr(flag.find_first_not_of('-'));
  std::replace(keyword.begin(), keyword.end(), '-', '_');
  return keyword;
}

// CLI11's messages name options as flags; a Python caller knows them as keywords.
std::string InKeywordTerms(const std::string& message) {
  static const std::regex kFlag("--([a-z0-9][a-z0-9-]*)");
  std::string result;
  auto last = message.cbegin();
  for (std::sregex_iterator it(message.begin(), message.end(), kFlag), end; it != end; ++it) {
    result.append(last, message.cbegin() + it->position());
    result += KeywordOf(it->str());
    last = message.cbegin() + it->position() + it->length();
  }
  result.append(last, message.cend());
  return result;
}

std::string ValueText(py::handle value) {
  if (py::isinstance<py::float_>(value)) return py::repr(value);  // repr round-trips a double exactly
  if (py::hasattr(value, "__fspath__")) return py::module_::import("os").attr("fspath")(value).cast<std::string>();
  return py::str(value);
}

void AppendArguments(const std::string& flag, py::handle value, std::vector<std::string>& arguments) {
  if (value.is_none()) return;
  if (py::isinstance<py::bool_>(value)) {
    if (value.cast<bool>()) arguments.push_back(flag);
    return;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    for (const py::handle item : value) {
      arguments.push_back(flag);
      arguments.push_back(ValueText(item));
    }
    return;
  }
  arguments.push_back(flag);
  arguments.push_back(ValueText(value));
}

std::unique_ptr<CLI::App> MakeApp(const std::string& name, const OptionAdder& add_options) {
  auto app = std::make_unique<CLI::App>("", name);
  app->set_help_flag();
  add_options(app.get());
  return app;
}

}  // namespace

void ParseKeywords(const std::string& function, const py::kwargs& keywords, const OptionAdder& add_options) {
  const std::unique_ptr<CLI::App> app = MakeApp(function, add_options);
  std::vector<std::string> arguments;
  for (const auto& [key, value] : keywords) {
    const std::string keyword = key.cast<std::string>();
    const std::string flag = FlagOf(keyword);
    if (app->get_option_no_throw(flag) == nullptr)
      throw py::type_error(function + "() got an unexpected keyword argument '" + keyword + "'");
    AppendArguments(flag, value, arguments);
  }
  std::reverse(arguments.begin(), arguments.end());  // CLI11 takes a vector of arguments last-first
  try {
    app->parse(arguments);
  } catch (const CLI::ParseError& error) {
    throw Error(function + ": " + InKeywordTerms(error.what()));
  }
}

bool AnyKeywordOf(const py::kwargs& keywords, const OptionAdder& add_options) {
  const std::unique_ptr<CLI::App> app = MakeApp("", add_options);
  for (const auto& item : keywords)
    if (app->get_option_no_throw(FlagOf(item.first.cast<std::string>())) != nullptr) return true;
  return false;
}

std::string KeywordHelp(const OptionAdder& add_options) {
  const std::unique_ptr<CLI::App> app = MakeApp("", add_options);
  std::string help;
  for (const CLI::Option* option : app->get_options()) {
    const std::string keyword = KeywordOf(option->get_name());
    const bool flag = option->get_type_size() == 0 || option->get_type_name().empty();
    std::string line = "    " + keyword + (flag ? " (flag: True sets it)" : " (" + option->get_type_name());
    if (!flag) {
      const std::string default_value = option->get_default_str();
      line += default_value.empty() ? ")" : ", default " + default_value + ")";
    }
    help += line + "\n        " + option->get_description() + "\n";
  }
  return help;
}

}  // namespace lfsp::python
