#pragma once

#include <H5Cpp.h>

namespace lfsp {

// What HDF5 allocates to read a dataset is sized by the file's declarations, not only by the dataset's shape: one
// buffer per chunk (zeroed), and conversion buffers of the stored element size. A corrupt or hostile file declaring
// 4 GiB chunks or a 4-GiB "float" cost that much memory on a 5 KB input (a fuzzer found both). Checks, before any
// read, that the stored elements are numbers of at most 8 bytes and applies the declared-size rule (input_limits.h)
// to the chunk against the file's real size; lfsp::Error naming the file and the dataset otherwise.
void CheckDeclaredStorage(const H5::DataSet& dataset);

}  // namespace lfsp
