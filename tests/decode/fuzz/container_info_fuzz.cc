// Fuzz target: `lfsp info` and `lfsp info --extract` on a Lytro file: the description, the extraction plan (file
// names from the container's own records) and the files it writes, which must all land inside the output folder and
// add up to a bounded multiple of the input (a table of contents listing one frame 100,000 times wrote 17 GB).
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

constexpr std::uintmax_t kMaxExpansion = 256;     // pretty-printed JSON of at most 100 levels: under 200x its text
constexpr std::uintmax_t kSlackBytes = 1u << 20;  // the manifest's fixed part

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
    std::uintmax_t bytes_written = 0;
    for (const fs::path& written : lfsp::decode::ExtractLytroFile(input, out)) {
      const fs::path inside = fs::weakly_canonical(written);
      const std::string folder = fs::weakly_canonical(out).string() + "/";
      if (inside.string().rfind(folder, 0) != 0)
        throw std::logic_error("extracted outside its folder: " + written.string());
      bytes_written += fs::file_size(written);
    }
    // Payloads are written once (at most the input's size); the JSON descriptions, pretty-printed, are the rest.
    if (bytes_written > kMaxExpansion * size + kSlackBytes)
      throw std::logic_error("extracted " + std::to_string(bytes_written) + " bytes from " + std::to_string(size));
  } catch (const lfsp::Error&) {
    // expected for malformed input
  }
  return 0;
}
