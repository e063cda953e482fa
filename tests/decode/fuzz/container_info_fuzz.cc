// Fuzz target: `lfsp info` and `lfsp info --extract` on a Lytro file: the description, the extraction plan (file
// names from the container's own records) and the files it writes, which must all land inside the output folder.
// Bad input must end in lfsp::Error; any other exception or a crash is a bug.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "../../core/fuzz/fuzz_file.h"
#include "fuzz_target.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/container_info.h"

namespace {

namespace fs = std::filesystem;

fs::path WorkFolder() {
  static const fs::path folder = [] {
    const fs::path path = fs::temp_directory_path() / ("lfsp-fuzz-info-" + std::to_string(getpid()));
    RemoveAtExit(path);
    return path;
  }();
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fs::path input = WorkFolder() / "capture.lfp";
  const fs::path out = WorkFolder() / "extracted";
  fs::remove_all(WorkFolder());
  fs::create_directories(WorkFolder());
  {
    std::ofstream file(input, std::ios::binary);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    (void)lfsp::decode::FormatLytroDescription(lfsp::decode::DescribeLytroFile(input));
    for (const fs::path& written : lfsp::decode::ExtractLytroFile(input, out)) {
      const fs::path inside = fs::weakly_canonical(written);
      const std::string folder = fs::weakly_canonical(out).string() + "/";
      if (inside.string().rfind(folder, 0) != 0)
        throw std::logic_error("extracted outside its folder: " + written.string());
    }
  } catch (const lfsp::Error&) {
    // expected for malformed input
  }
  return 0;
}
