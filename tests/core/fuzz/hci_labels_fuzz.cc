// Fuzz target: the old HCI layout's labels (lf.h5 without a labels dataset, and a sibling labels.h5 whose GT_LABELS
// ReadBundle reads for it). The input is labels.h5; lf.h5 beside it is a valid 3 x 3 view, 8 x 6 pixel bundle written
// once per process (the bundle target fuzzes lf.h5 itself). Read as every stage reads it: the whole bundle, a block
// of its views (LoadCentralViews keeps the central ones), and labels.h5 alone (ReadLabels, what recolor and evaluate
// read). Bad input must end in lfsp::Error naming labels.h5 (lf.h5 is valid: a message naming only lf.h5 blames the
// wrong file); any other exception or a crash is a bug.

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "../../decode/fuzz/fuzz_target.h"
#include "fuzz_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/hdf5_bundle.h"

namespace {

namespace fs = std::filesystem;

// The folder holding lf.h5 (written on first use) and each input's labels.h5.
fs::path WorkFolder() {
  static const fs::path folder = [] {
    const fs::path path = fs::temp_directory_path() / ("lfsp-fuzz-hci-labels-" + std::to_string(getpid()));
    RemoveAtExit(path);
    fs::remove_all(path);
    fs::create_directories(path);
    // Written by a child process: libhdf5 keeps blocks from writing a file that libFuzzer's leak check, run after
    // each input, reports as leaked (none is at exit); the fuzzing process then only reads.
    const pid_t child = fork();
    if (child == 0) {
      try {
        lfsp::Bundle bundle;
        bundle.light_field = lfsp::LightField(lfsp::LightFieldShape{3, 3, 8, 6, 3});
        float* samples = bundle.light_field.data();
        for (std::size_t i = 0; i < bundle.light_field.size(); ++i) samples[i] = static_cast<float>(i % 256) / 255.0f;
        lfsp::WriteBundle(bundle, path / "lf.h5", {lfsp::SampleStorage::kUint8, 0});
      } catch (...) {
        _exit(1);
      }
      _exit(0);
    }
    int status = 0;
    if (child < 0 || waitpid(child, &status, 0) != child || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
      throw std::runtime_error("cannot write " + (path / "lf.h5").string());
    return path;
  }();
  return folder;
}

// Every problem is labels.h5's, and the message must say so.
void RequireNamesLabels(const lfsp::Error& error, const fs::path& labels) {
  if (std::string(error.what()).find(labels.string()) == std::string::npos)
    throw std::logic_error(std::string("error does not name ") + labels.string() + ": " + error.what());
}

}  // namespace

// libFuzzer calls this before the first input, so the first input's time is its own. The replay driver does not
// (WorkFolder writes lf.h5 on first use).
extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  (void)WorkFolder();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fs::path lf = WorkFolder() / "lf.h5";
  const fs::path labels = WorkFolder() / "labels.h5";
  {
    std::ofstream file(labels, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    (void)lfsp::ReadBundle(lf);
  } catch (const lfsp::Error& error) {
    RequireNamesLabels(error, labels);
  }
  try {
    lfsp::BundleParts parts;
    parts.views = lfsp::ViewBlock{{1, 0}, 2, 2};
    parts.samples = false;
    (void)lfsp::ReadBundle(lf, parts);
  } catch (const lfsp::Error& error) {
    RequireNamesLabels(error, labels);
  }
  try {
    (void)lfsp::ReadLabels(labels);
  } catch (const lfsp::Error& error) {
    RequireNamesLabels(error, labels);
  }
  return 0;
}
