// Fuzz target: a folder of views in any tool's layout (FindViewsLayout's naming detection, parameters.cfg, the
// views' headers and pixels, HCI weight_Cam### files, a disparity.pfm beside them), read as `lfsp` reads a light
// field given as a folder (LooksLikeViewsFolder, then LoadLightField). The input is the folder's files
// (fuzz_folder.h); an entry named views_pattern is taken out of the folder and given as --views-pattern.
// Bad input must end in lfsp::Error; any other exception or a crash is a bug.

#include <fstream>
#include <string>

#include "../../decode/fuzz/fuzz_target.h"
#include "fuzz_folder.h"
#include "lfsp/core/error.h"
#include "lfsp/core/load.h"
#include "lfsp/core/views_folder.h"
#include "lfsp/core/views_naming.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path folder = FuzzInputFolder(data, size, "views");
  lfsp::LoadOptions options;
  const std::filesystem::path pattern_file = folder / "views_pattern";
  std::error_code ec;
  if (std::filesystem::is_regular_file(pattern_file, ec)) {
    std::ifstream in(pattern_file, std::ios::binary);
    std::getline(in, options.views_pattern);
    in.close();
    std::filesystem::remove(pattern_file, ec);
  }
  (void)lfsp::LooksLikeViewsFolder(folder);
  try {
    (void)lfsp::FindViewsLayout(folder, options.views_pattern);
  } catch (const lfsp::Error&) {
  }
  try {
    (void)lfsp::LoadLightField(folder, options);
  } catch (const lfsp::Error&) {
  }
  return 0;
}
