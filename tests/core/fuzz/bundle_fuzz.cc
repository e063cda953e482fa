// Fuzz target: the .h5 bundle every stage reads and writes (ReadBundle), its labels alone (ReadLabels, what
// recolor and evaluate read), and the loading of only the views a stage keeps (LoadCentralViews: the views' mean
// weights, then a block of views), on the same bytes.

#include "../../decode/fuzz/fuzz_target.h"
#include "fuzz_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/load.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = FuzzInputFile(data, size, ".h5");
  try {
    (void)lfsp::ReadBundle(file);
  } catch (const lfsp::Error&) {
  }
  try {
    (void)lfsp::ReadLabels(file);
  } catch (const lfsp::Error&) {
  }
  try {
    (void)lfsp::LoadCentralViews(file, 0);
  } catch (const lfsp::Error&) {
  }
  return 0;
}
