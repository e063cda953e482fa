#pragma once

#include <filesystem>

namespace lfsp {

// An output written under a temporary name beside its destination and renamed into place by Commit(), so an
// interrupted run never leaves a half-written result that looks whole. Unless committed, the temporary is removed.
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

}  // namespace lfsp
