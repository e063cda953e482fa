// Fuzz target: a folder of white images (BuildWhiteImageDatabase: MOD_####.TXT + .RAW pairs in any subfolder, and
// calibration archives data.C.N), then what a decode does with the database: LoadOrBuildWhiteImageDatabase (a
// whites.json in the folder is read instead when it is as new as the white images), SelectWhiteImage for a capture
// with the first white image's metadata, and the chosen and first entries' raw images and metadata. The input is the
// folder's files (../../core/fuzz/fuzz_folder.h; names may hold '/'). Bad input must end in lfsp::Error; any other
// exception or a crash is a bug.

#include "../../core/fuzz/fuzz_folder.h"
#include "fuzz_target.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/white_database.h"

namespace {

// What a decode reads of one entry.
void ReadEntry(const lfsp::decode::WhiteImageEntry& entry) {
  try {
    (void)lfsp::decode::ReadWhiteImageRaw(entry);
  } catch (const lfsp::Error&) {
  }
  try {
    (void)lfsp::decode::ReadWhiteImageMetadata(entry);
  } catch (const lfsp::Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path folder = FuzzInputFolder(data, size, "whites", /*subfolders=*/true);
  try {
    const lfsp::decode::WhiteImageDatabase built = lfsp::decode::BuildWhiteImageDatabase(folder);
    (void)lfsp::decode::WhiteImageDatabaseJson(built, folder).dump();
  } catch (const lfsp::Error&) {
  }
  try {
    const lfsp::decode::WhiteImageDatabase database = lfsp::decode::LoadOrBuildWhiteImageDatabase(folder);
    if (database.entries.empty()) return 0;
    ReadEntry(database.entries.front());
    const lfsp::decode::LytroMetadata capture = lfsp::decode::ReadWhiteImageMetadata(database.entries.front());
    const lfsp::decode::WhiteImageChoice choice = lfsp::decode::SelectWhiteImage(database, capture);
    if (choice.entry != &database.entries.front()) ReadEntry(*choice.entry);
  } catch (const lfsp::Error&) {
  }
  return 0;
}
