#pragma once

#include <cstdint>
#include <string>

namespace lfsp::testing {

// A well-formed PNG (valid CRCs) of 57 bytes that declares width x height RGB8 and holds one empty IDAT: a file
// whose declared size lies, for the checks that must refuse it before allocating.
std::string PngDeclaring(std::uint32_t width, std::uint32_t height);

}  // namespace lfsp::testing
