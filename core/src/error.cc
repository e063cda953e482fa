#include "lfsp/core/error.h"

namespace lfsp {

std::string FileMessage(const std::string& path, const std::string& problem) { return path + ": " + problem; }

void ThrowFileError(const std::string& path, const std::string& problem) { throw Error(FileMessage(path, problem)); }

}  // namespace lfsp
