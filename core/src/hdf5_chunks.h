#pragma once

#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace lfsp {

// Fills `chunk` with one view's bytes as the dataset stores them (chunk_elements x element_size bytes): views are
// produced a batch at a time, so a converted copy of a whole light field is never held. Called from several threads.
using ViewChunkSource = std::function<void(std::size_t view, std::uint8_t* chunk)>;

// Writes a dataset chunked one view per chunk (dims [nv][nu][...], as ChunkedPerView makes it with shuffle and
// deflate) by compressing the chunks in parallel and handing them to HDF5 whole (H5Dwrite_chunk): HDF5 runs its
// filters on one thread, which made a full Illum decode take 16.6 s to write. `source` gives each of the `views`
// chunks of `chunk_elements` elements of `element_size` bytes, in the dataset's stored type, views in [v][u] order;
// `nu` is the angular width and `rank` the dataset's rank. Throws lfsp::Error naming `name` on failure.
void WriteViewChunks(hid_t dataset, const ViewChunkSource& source, std::size_t element_size, std::size_t views, int nu,
                     std::size_t chunk_elements, int rank, int level, const std::string& name);

// The reverse of WriteViewChunks, for the datasets it writes: the raw chunks are read in order by HDF5
// (H5Dread_chunk) and inflated and unshuffled in parallel into `destination`, which holds `count` elements of the
// dataset's type, given as `memory_type` (a native type the stored one must equal). HDF5 inflates on one thread:
// `lfsp depth` loaded a full-size 15x15 Illum decode (uint16) in 2.8-3.4 s, now 2.0-2.2 s. Returns false when the
// dataset is laid out otherwise (not one view per chunk, other filters, filter parameters or types, a chunk not
// stored or stored with a filter skipped); `destination` may then hold some views already, and the caller reads the
// whole dataset through HDF5. Throws lfsp::Error naming `name` when reading a raw chunk fails, when the chunks'
// declared sizes add up to more than the file, or when a chunk does not inflate to exactly its size. With
// `first_view`, the views from camera number `first_view` on (`count` elements: whole views) are read, without the
// rest.
bool ReadViewChunks(hid_t dataset, hid_t memory_type, void* destination, std::size_t count, const std::string& name,
                    std::size_t first_view = 0);

}  // namespace lfsp
