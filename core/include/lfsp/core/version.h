#pragma once

namespace lfsp {

// lfsp's version, e.g. "0.1.0" or "0.1.0+3.g1a2b3c4" (cmake/LfspVersion.cmake: git tags, else the VERSION file).
const char* Version();

}  // namespace lfsp
