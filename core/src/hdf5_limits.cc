#include "hdf5_limits.h"

#include <string>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/input_limits.h"

namespace lfsp {
namespace {

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
}

}  // namespace lfsp
