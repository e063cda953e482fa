#include "lfsp/core/error.h"

namespace lfsp {

std::string FileMessage(const std::string& path, const std::string& problem) { return path + ": " + problem; }

void ThrowFileError(const std::string& path, const std::string& problem) { throw Error(FileMessage(path, problem)); }

namespace {
std::string KeepApiName(const std::string& api_name) { return api_name; }
OptionNamer g_option_namer = KeepApiName;
}  // namespace

std::string OptionName(const std::string& api_name) { return g_option_namer(api_name); }

void SetOptionNamer(OptionNamer namer) { g_option_namer = namer != nullptr ? namer : KeepApiName; }

}  // namespace lfsp
