#include "hdf5_contiguous.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/parallel_for.h"

namespace lfsp {
namespace {

// True if `dataset` holds its `elements` elements of `memory_type` in one unfiltered block inside its own file.
bool StoredContiguously(hid_t dataset, hid_t memory_type, std::size_t elements) {
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
  return same_type && points >= 0 && static_cast<std::size_t>(points) == elements &&
         H5Dget_storage_size(dataset) == elements * H5Tget_size(memory_type);
}

// The file holding a dataset, with HDF5's own descriptor of it: the very file HDF5 read the dataset's layout from,
// whatever has since happened to its name (a bundle renamed over it, a relative path). The descriptor is -1 unless
// the file was opened with the default (sec2) driver, whose handle is a POSIX descriptor; pread on it is safe from
// several threads.
class FileOf {
 public:
  explicit FileOf(hid_t dataset) : file_(H5Iget_file_id(dataset)) {
    if (file_ < 0) return;
    const hid_t access = H5Fget_access_plist(file_);
    const bool sec2 = access >= 0 && H5Pget_driver(access) == H5FD_SEC2;
    if (access >= 0) H5Pclose(access);
    void* handle = nullptr;
    if (sec2 && H5Fget_vfd_handle(file_, H5P_DEFAULT, &handle) >= 0 && handle != nullptr)
      fd_ = *static_cast<int*>(handle);
  }
  ~FileOf() {
    if (file_ >= 0) H5Fclose(file_);
  }
  FileOf(const FileOf&) = delete;
  FileOf& operator=(const FileOf&) = delete;
  int fd() const { return fd_; }

 private:
  hid_t file_;
  int fd_ = -1;
};

// The number of elements of `dataset`, or 0 if unknown.
std::size_t ElementCount(hid_t dataset) {
  const hid_t space = H5Dget_space(dataset);
  const hssize_t points = space >= 0 ? H5Sget_simple_extent_npoints(space) : -1;
  if (space >= 0) H5Sclose(space);
  return points > 0 ? static_cast<std::size_t>(points) : 0;
}

}  // namespace

bool ReadContiguous(hid_t dataset, hid_t memory_type, void* destination, std::size_t count, const std::string& name,
                    std::size_t first) {
  const std::size_t elements = ElementCount(dataset);
  if (count == 0 || first > elements || count > elements - first || !StoredContiguously(dataset, memory_type, elements))
    return false;
  const haddr_t start = H5Dget_offset(dataset);  // from the beginning of the file, past any user block
  const FileOf file(dataset);
  struct stat status {};
  if (start == HADDR_UNDEF || file.fd() < 0 || fstat(file.fd(), &status) != 0) return false;
  const auto file_bytes = static_cast<std::uintmax_t>(status.st_size);
  const std::size_t element_size = H5Tget_size(memory_type);
  const std::size_t bytes = count * element_size;
  const std::uintmax_t offset = start + first * element_size;
  if (offset > file_bytes || bytes > file_bytes - offset)
    ThrowFileError(name, "declares " + std::to_string(bytes) + " bytes at offset " + std::to_string(offset) +
                             ", beyond the end of the " + std::to_string(file_bytes) + "-byte file");
  constexpr std::size_t kPiece = std::size_t{16} << 20;
  auto* out = static_cast<char*>(destination);
  ParallelFor(static_cast<int>((bytes + kPiece - 1) / kPiece), [&](int piece) {
    const std::size_t begin = static_cast<std::size_t>(piece) * kPiece, end = std::min(bytes, begin + kPiece);
    for (std::size_t done = begin; done < end;) {
      const ssize_t got = pread(file.fd(), out + done, end - done, static_cast<off_t>(offset + done));
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) ThrowFileError(name, "reading " + std::to_string(end - done) + " bytes failed");
      done += static_cast<std::size_t>(got);
    }
  });
  return true;
}

}  // namespace lfsp
