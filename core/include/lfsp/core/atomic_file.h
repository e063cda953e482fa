#pragma once

#include <filesystem>

namespace lfsp {

// An output written under a temporary name beside its destination and renamed into place by Commit(), so an
// interrupted run never leaves a half-written result that looks whole. Unless committed, the temporary is removed;
// the temporaries a killed run left for the same destination (out.tmp-<digits>.ext) are removed when the next
// AtomicOutput for it is made. One writer per destination at a time.
class AtomicOutput {
 public:
  explicit AtomicOutput(std::filesystem::path destination);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  const std::filesystem::path& temporary() const { return temporary_; }
  const std::filesystem::path& destination() const { return destination_; }
  void Commit();  // replaces the destination (file or folder) with the temporary

 private:
  std::filesystem::path destination_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

// Removes what interrupted runs left for `destination`: siblings named as AtomicOutput names its temporaries.
void RemoveStaleTemporaries(const std::filesystem::path& destination);

}  // namespace lfsp
