#pragma once

#include <hdf5.h>

#include <cstddef>
#include <string>

namespace lfsp {

// Writes a dataset chunked one view per chunk (dims [nv][nu][...], as ChunkedPerView makes it with shuffle and
// deflate) by compressing the chunks in parallel and handing them to HDF5 whole (H5Dwrite_chunk): HDF5 runs its
// filters on one thread, which made a full Illum decode take 16.6 s to write. `data` holds `views` chunks of
// `chunk_elements` elements of `element_size` bytes each, in the dataset's stored type, views in [v][u] order;
// `nu` is the angular width and `rank` the dataset's rank. Throws lfsp::Error naming `name` on failure.
void WriteViewChunks(hid_t dataset, const void* data, std::size_t element_size, std::size_t views, int nu,
                     std::size_t chunk_elements, int rank, int level, const std::string& name);

}  // namespace lfsp
