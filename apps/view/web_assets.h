#pragma once

// The page's files (apps/view/web/*), embedded into the binary at build time (cmake/embed_files.cmake), so the
// viewer needs no files beside it and no internet.

#include <cstddef>
#include <span>
#include <string_view>

namespace lfsp::view {

struct WebAsset {
  std::string_view name;  // file name, e.g. "app.js"
  std::string_view bytes;
};

std::span<const WebAsset> WebAssets();

}  // namespace lfsp::view
