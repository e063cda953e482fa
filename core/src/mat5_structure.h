#pragma once
// The structure of a MATLAB v5 .mat file, checked before libmatio reads it. matio trusts what the file declares:
// a truncated file reads back as zeros, and a variable header declaring a dimensions array of a gigabyte makes it
// allocate and fill that much from an 882-byte file. So the top-level data elements are walked first.

#include <filesystem>

namespace lfsp {

// Throws lfsp::Error naming the file unless every top-level data element ends inside the file and every variable's
// header (inflated first when compressed) declares a dimensions array of at most kMaxMatDimensions entries and a
// name of plausible length.
void CheckMat5Structure(const std::filesystem::path& path);

}  // namespace lfsp
