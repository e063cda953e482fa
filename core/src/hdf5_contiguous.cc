#include "hdf5_contiguous.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/parallel_for.h"

namespace lfsp {
namespace {

// True if `dataset` holds its `count` elements of `memory_type` in one unfiltered block inside its own file.
bool StoredContiguously(hid_t dataset, hid_t memory_type, std::size_t count) {
  const hid_t properties = H5Dget_create_plist(dataset);
  if (properties < 0) return false;
  const bool plain = H5Pget_layout(properties) == H5D_CONTIGUOUS && H5Pget_nfilters(properties) == 0 &&
                     H5Pget_external_count(properties) == 0;
  H5Pclose(properties);
  if (!plain) return false;
  const hid_t type = H5Dget_type(dataset);
  const bool same_type = type >= 0 && H5Tequal(type, memory_type) > 0;
  if (type >= 0) H5Tclose(type);
  const hid_t space = H5Dget_space(dataset);
  const hssize_t points = space >= 0 ? H5Sget_simple_extent_npoints(space) : -1;
  if (space >= 0) H5Sclose(space);
  return same_type && points >= 0 && static_cast<std::size_t>(points) == count &&
         H5Dget_storage_size(dataset) == count * H5Tget_size(memory_type);
}

// The name the file holding `dataset` was opened by ("" if HDF5 cannot say).
std::string FileNameOf(hid_t dataset) {
  const hid_t file = H5Iget_file_id(dataset);
  if (file < 0) return "";
  const ssize_t length = H5Fget_name(file, nullptr, 0);
  std::string path(length > 0 ? static_cast<std::size_t>(length) : 0, '\0');
  if (length > 0 && H5Fget_name(file, path.data(), path.size() + 1) != length) path.clear();
  H5Fclose(file);
  return path;
}

class ReadOnlyFile {
 public:
  explicit ReadOnlyFile(const std::string& path) : fd_(open(path.c_str(), O_RDONLY | O_CLOEXEC)) {}
  ~ReadOnlyFile() {
    if (fd_ >= 0) close(fd_);
  }
  ReadOnlyFile(const ReadOnlyFile&) = delete;
  ReadOnlyFile& operator=(const ReadOnlyFile&) = delete;
  int fd() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

bool ReadContiguous(hid_t dataset, hid_t memory_type, void* destination, std::size_t count, const std::string& name) {
  if (count == 0 || !StoredContiguously(dataset, memory_type, count)) return false;
  const haddr_t offset = H5Dget_offset(dataset);  // from the beginning of the file, past any user block
  const std::string path = FileNameOf(dataset);
  std::error_code ec;
  const std::uintmax_t file_bytes = path.empty() ? 0 : std::filesystem::file_size(path, ec);
  if (offset == HADDR_UNDEF || path.empty() || ec) return false;
  const std::size_t bytes = count * H5Tget_size(memory_type);
  if (offset > file_bytes || bytes > file_bytes - offset)
    ThrowFileError(name, "declares " + std::to_string(bytes) + " bytes at offset " + std::to_string(offset) +
                             ", beyond the end of the " + std::to_string(file_bytes) + "-byte file");
  const ReadOnlyFile file(path);
  if (file.fd() < 0) return false;
  constexpr std::size_t kPiece = std::size_t{16} << 20;
  auto* out = static_cast<char*>(destination);
  ParallelFor(static_cast<int>((bytes + kPiece - 1) / kPiece), [&](int piece) {
    const std::size_t begin = static_cast<std::size_t>(piece) * kPiece, end = std::min(bytes, begin + kPiece);
    for (std::size_t done = begin; done < end;) {
      const ssize_t got = pread(file.fd(), out + done, end - done, static_cast<off_t>(offset + done));
      if (got <= 0) ThrowFileError(name, "reading " + std::to_string(end - done) + " bytes failed");
      done += static_cast<std::size_t>(got);
    }
  });
  return true;
}

}  // namespace lfsp
