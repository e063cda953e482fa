#include "lfsp/core/atomic_file.h"

#include <random>
#include <system_error>

#include "lfsp/core/error.h"

namespace lfsp {
namespace fs = std::filesystem;

namespace {
fs::path TemporaryNameFor(const fs::path& destination) {
  std::random_device device;
  const unsigned tag = device();
  // Keep the extension last ("out.tmp-123.png") so format detection by extension still works on the temporary.
  fs::path name = destination.stem();
  name += ".tmp-" + std::to_string(tag);
  name += destination.extension();
  return destination.parent_path() / name;
}
}  // namespace

AtomicOutput::AtomicOutput(fs::path destination)
    : destination_(std::move(destination)), temporary_(TemporaryNameFor(destination_)) {
  const fs::path parent = destination_.parent_path();
  std::error_code ec;
  if (!parent.empty() && !fs::exists(parent, ec)) {
    fs::create_directories(parent, ec);
    if (ec) ThrowFileError(parent.string(), "cannot create output folder: " + ec.message());
  }
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(temporary_, ec);
  }
}

void AtomicOutput::Commit() {
  std::error_code ec;
  if (fs::is_directory(temporary_, ec) && fs::exists(destination_, ec)) {
    // rename() cannot replace a non-empty folder: move the old one aside first, drop it after the swap.
    fs::path old = TemporaryNameFor(destination_);
    fs::rename(destination_, old, ec);
    if (ec) ThrowFileError(destination_.string(), "cannot replace existing output: " + ec.message());
    fs::rename(temporary_, destination_, ec);
    if (ec) {
      fs::rename(old, destination_);
      ThrowFileError(destination_.string(), "cannot move finished output into place: " + ec.message());
    }
    fs::remove_all(old, ec);
  } else {
    fs::rename(temporary_, destination_, ec);
    if (ec) ThrowFileError(destination_.string(), "cannot move finished output into place: " + ec.message());
  }
  committed_ = true;
}

}  // namespace lfsp
