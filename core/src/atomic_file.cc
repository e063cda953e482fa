#include "lfsp/core/atomic_file.h"

#include <random>
#include <string>
#include <system_error>
#include <vector>

#include "lfsp/core/error.h"

namespace lfsp {
namespace fs = std::filesystem;

namespace {

constexpr const char* kTemporaryTag = ".tmp-";

fs::path TemporaryNameFor(const fs::path& destination) {
  std::random_device device;
  const unsigned tag = device();
  // Keep the extension last ("out.tmp-123.png") so format detection by extension still works on the temporary.
  fs::path name = destination.stem();
  name += kTemporaryTag + std::to_string(tag);
  name += destination.extension();
  return destination.parent_path() / name;
}

// Whether `name` is TemporaryNameFor(destination) for some tag: stem, ".tmp-", digits, extension.
bool IsTemporaryNameOf(const std::string& name, const fs::path& destination) {
  const std::string prefix = destination.stem().string() + kTemporaryTag;
  const std::string extension = destination.extension().string();
  if (name.size() <= prefix.size() + extension.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
    return false;
  const std::string tag = name.substr(prefix.size(), name.size() - prefix.size() - extension.size());
  return tag.find_first_not_of("0123456789") == std::string::npos;
}

// "out/" names the folder "out": its temporary goes beside it ("out.tmp-N"), not inside it.
fs::path WithoutTrailingSeparator(fs::path destination) {
  if (!destination.has_filename() && destination.has_parent_path()) destination = destination.parent_path();
  const std::string name = destination.filename().string();
  if (name.empty() || name == "." || name == "..")
    ThrowFileError(destination.string(), "an output needs a name of its own (not '.' or '..')");
  return destination;
}

}  // namespace

void RemoveStaleTemporaries(const fs::path& destination) {
  std::error_code ec;
  const fs::path parent = destination.parent_path().empty() ? fs::path(".") : destination.parent_path();
  if (!fs::is_directory(parent, ec)) return;
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(parent, ec))
    if (IsTemporaryNameOf(entry.path().filename().string(), destination)) stale.push_back(entry.path());
  for (const fs::path& path : stale) fs::remove_all(path, ec);
}

AtomicOutput::AtomicOutput(fs::path destination)
    : destination_(WithoutTrailingSeparator(std::move(destination))), temporary_(TemporaryNameFor(destination_)) {
  const fs::path parent = destination_.parent_path();
  std::error_code ec;
  if (!parent.empty() && !fs::exists(parent, ec)) {
    fs::create_directories(parent, ec);
    if (ec) ThrowFileError(parent.string(), "cannot create output folder: " + ec.message());
  }
  RemoveStaleTemporaries(destination_);
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
