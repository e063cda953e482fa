#include "hdf5_limits.h"

#include <cstdint>
#include <string>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/input_limits.h"

namespace lfsp {
namespace {

// What libhdf5 holds for each chunk a read covers (measured about 6.7 KB with 1.10 on Debian 12).
constexpr std::uint64_t kHdf5BytesPerChunk = 8192;

// A name HDF5 reports through a (buffer, size) call that returns the length; "?" when it has none.
template <typename GetName>
std::string HdfName(GetName get_name) {
  const ssize_t length = get_name(nullptr, 0);
  if (length <= 0) return "?";
  std::string name(static_cast<std::size_t>(length) + 1, '\0');
  get_name(name.data(), name.size());
  name.resize(static_cast<std::size_t>(length));
  return name;
}

}  // namespace

void CheckDeclaredStorage(const H5::DataSet& dataset) {
  const hid_t file = H5Iget_file_id(dataset.getId());  // a new reference, closed below
  hsize_t file_bytes = 0;
  H5Fget_filesize(file, &file_bytes);
  const std::string file_name = HdfName([&](char* name, std::size_t size) { return H5Fget_name(file, name, size); });
  H5Fclose(file);
  const std::string where = file_name + ": dataset " + HdfName([&](char* name, std::size_t size) {
                              return H5Iget_name(dataset.getId(), name, size);
                            });

  const H5T_class_t type_class = dataset.getTypeClass();
  const std::size_t element_bytes = dataset.getDataType().getSize();
  if ((type_class == H5T_INTEGER || type_class == H5T_FLOAT) && (element_bytes == 0 || element_bytes > 8))
    ThrowFileError(where, "declares numbers of " + std::to_string(element_bytes) + " bytes each (at most 8)");

  const H5::DSetCreatPropList properties = dataset.getCreatePlist();
  if (properties.getLayout() != H5D_CHUNKED) return;
  const int rank = properties.getChunk(0, nullptr);
  if (rank <= 0) return;
  std::vector<hsize_t> chunk(static_cast<std::size_t>(rank));
  properties.getChunk(rank, chunk.data());
  CheckDeclaredAllocation(where + " chunks", SaturatingBytes({chunk.begin(), chunk.end()}, element_bytes), file_bytes);

  // libhdf5 also keeps a record of every chunk a read covers, written or not: tiny chunks over a large shape cost it
  // gigabytes on a small file (fuzz finding, core/fuzz_hci_labels: 196,599 chunks of 1x1x6x8 in a 5 KB labels.h5
  // took 1.3 GB, about 6.7 KB per chunk). The chunk count is held to the same rule, at kHdf5BytesPerChunk each.
  const H5::DataSpace space = dataset.getSpace();
  std::vector<hsize_t> dims(static_cast<std::size_t>(space.getSimpleExtentNdims()));
  space.getSimpleExtentDims(dims.data());
  if (dims.size() != chunk.size()) return;
  std::vector<std::uint64_t> chunks_per_dimension;
  for (std::size_t i = 0; i < dims.size(); ++i)
    chunks_per_dimension.push_back(chunk[i] == 0 ? 0 : dims[i] / chunk[i] + (dims[i] % chunk[i] != 0 ? 1 : 0));
  const std::uint64_t chunk_count = SaturatingBytes(chunks_per_dimension, 1);
  CheckDeclaredAllocation(where + " (" + std::to_string(chunk_count) + " chunks: libhdf5's record of each)",
                          SaturatingBytes({chunk_count}, kHdf5BytesPerChunk), file_bytes);
}

}  // namespace lfsp
