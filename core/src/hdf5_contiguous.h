#pragma once

#include <hdf5.h>

#include <cstddef>
#include <string>

namespace lfsp {

// Reads a contiguous, unfiltered dataset stored as `memory_type` (a native type the stored one must equal) straight
// from its file into `destination` (`count` elements), in pieces of 16 MB read on all cores: HDF5 copies it on one
// thread, and the simulator's uncompressed ground truth (1.09 GB) took 1.0-1.8 s of every pipeline on a simulated
// Illum capture. Returns false when the dataset is laid out otherwise (chunked, filtered, external, not allocated,
// another type or size) and the caller reads it through HDF5. Throws lfsp::Error naming `name` when the dataset's
// declared place lies outside the file or a read fails. With `first`, the `count` elements from element `first` on
// (in the dataset's row-major order) are read: a run of views of a light field, without the rest.
bool ReadContiguous(hid_t dataset, hid_t memory_type, void* destination, std::size_t count, const std::string& name,
                    std::size_t first = 0);

}  // namespace lfsp
