#include "hdf5_chunks.h"

#include <libdeflate.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/parallel_for.h"

namespace lfsp {
namespace {

// A byte plane whose samples deflate to at least this fraction of their size is stored as it is.
constexpr double kIncompressible = 0.98;

// HDF5's shuffle filter: byte k of every element, then byte k + 1, ... (all byte planes in turn).
std::vector<std::uint8_t> Shuffled(const std::uint8_t* bytes, std::size_t elements, std::size_t element_size) {
  std::vector<std::uint8_t> out(elements * element_size);
  for (std::size_t b = 0; b < element_size; ++b) {
    std::uint8_t* plane = out.data() + b * elements;
    for (std::size_t i = 0; i < elements; ++i) plane[i] = bytes[i * element_size + b];
  }
  return out;
}

// Whether deflate would leave a byte plane as large as it is (a decode's low sample bytes are sensor noise: level 1
// deflated them to 100.0 % of their size, in half the time the whole chunk took). Asked of deflate itself, on four
// samples of 4 KiB spread over the plane: 1-2 % of deflating it all. The byte histogram alone cannot tell: the
// low bytes of labels are evenly spread too, yet deflate to a tenth in runs.
bool LooksIncompressible(libdeflate_compressor* compressor, const std::uint8_t* plane, std::size_t bytes) {
  constexpr std::size_t kSample = 4096, kSamples = 4;
  std::array<std::uint8_t, 2 * kSample> scratch;
  std::size_t sampled = 0, deflated = 0;
  for (std::size_t k = 0; k < kSamples; ++k) {
    const std::size_t length = std::min(kSample, bytes);
    const std::size_t start = bytes <= kSample ? 0 : (bytes - kSample) * k / (kSamples - 1);
    const std::size_t size =
        libdeflate_deflate_compress(compressor, plane + start, length, scratch.data(), scratch.size());
    sampled += length;
    deflated += size == 0 ? length : size;
    if (bytes <= kSample) break;
  }
  return sampled == 0 || static_cast<double>(deflated) >= kIncompressible * static_cast<double>(sampled);
}

// Appends `count` bytes as uncompressed DEFLATE blocks (BTYPE 00), none of them final: each starts on a byte
// boundary, a header byte 0 (BFINAL 0, BTYPE 00 and the padding), LEN and its one's complement, then the bytes.
void AppendStoredBlocks(const std::uint8_t* bytes, std::size_t count, std::vector<std::uint8_t>& out) {
  constexpr std::size_t kLargestStoredBlock = 65535;
  for (std::size_t done = 0; done < count;) {
    const auto length = static_cast<std::uint16_t>(std::min(kLargestStoredBlock, count - done));
    const auto complement = static_cast<std::uint16_t>(~length);
    out.insert(out.end(), {0, static_cast<std::uint8_t>(length & 0xFF), static_cast<std::uint8_t>(length >> 8),
                           static_cast<std::uint8_t>(complement & 0xFF), static_cast<std::uint8_t>(complement >> 8)});
    out.insert(out.end(), bytes + done, bytes + done + length);
    done += length;
  }
}

// One shuffled chunk of `planes` byte planes as the zlib stream HDF5's deflate filter reads back, made by
// libdeflate: one whole-buffer call instead of zlib's streaming state. On one shuffled view of a full Illum light
// field at level 1 (this machine): float32 52 -> 28 ms for 59.5 -> 58.5 % of its size; 16-bit samples 16.7 ms (zlib
// with run-length matching only, which the files used before) -> 10.4 ms for 87 -> 59 %. The leading planes that
// deflate would not shrink (LooksIncompressible) are stored as they are and only the rest deflated, as one stream after
// them: still one zlib stream that any zlib reader inflates to the same bytes. Without such planes the stream is
// libdeflate's own, byte for byte.
bool DeflateChunk(const std::vector<std::uint8_t>& in, std::size_t planes, int level, std::vector<std::uint8_t>& out) {
  const std::unique_ptr<libdeflate_compressor, decltype(&libdeflate_free_compressor)> compressor(
      libdeflate_alloc_compressor(std::clamp(level, 1, 12)), libdeflate_free_compressor);
  if (!compressor) return false;
  const std::size_t plane_bytes = planes > 0 ? in.size() / planes : 0;
  std::size_t stored = 0;  // bytes of the leading planes that deflate would not shrink
  while (plane_bytes > 0 && stored < in.size() &&
         LooksIncompressible(compressor.get(), in.data() + stored, plane_bytes))
    stored += plane_bytes;
  if (stored == 0) {
    out.resize(libdeflate_zlib_compress_bound(compressor.get(), in.size()));
    const std::size_t size = libdeflate_zlib_compress(compressor.get(), in.data(), in.size(), out.data(), out.size());
    out.resize(size);
    return size > 0;
  }
  out.assign({0x78, 0x01});  // zlib header: deflate, 32 KiB window, fastest compression (a multiple of 31)
  AppendStoredBlocks(in.data(), stored, out);
  const std::size_t rest = in.size() - stored;
  // The deflated rest ends the stream with its final block; for a chunk of noise alone libdeflate writes an empty
  // final block.
  const std::size_t header = out.size();
  out.resize(header + libdeflate_deflate_compress_bound(compressor.get(), rest));
  const std::size_t size =
      libdeflate_deflate_compress(compressor.get(), in.data() + stored, rest, out.data() + header, out.size() - header);
  if (size == 0) return false;
  out.resize(header + size);
  const std::uint32_t adler = libdeflate_adler32(1, in.data(), in.size());
  out.insert(out.end(), {static_cast<std::uint8_t>(adler >> 24), static_cast<std::uint8_t>(adler >> 16),
                         static_cast<std::uint8_t>(adler >> 8), static_cast<std::uint8_t>(adler)});
  return true;
}

// Undoes Shuffled: byte plane b of `planes` holds byte b of every element.
void Unshuffle(const std::uint8_t* planes, std::size_t elements, std::size_t element_size, std::uint8_t* bytes) {
  for (std::size_t b = 0; b < element_size; ++b) {
    const std::uint8_t* plane = planes + b * elements;
    for (std::size_t i = 0; i < elements; ++i) bytes[i * element_size + b] = plane[i];
  }
}

// Inflates one zlib stream into exactly out.size() bytes; false if it is corrupt, shorter or longer (libdeflate,
// twice zlib's speed on these chunks).
bool InflateChunk(const std::vector<std::uint8_t>& in, std::vector<std::uint8_t>& out) {
  const std::unique_ptr<libdeflate_decompressor, decltype(&libdeflate_free_decompressor)> decompressor(
      libdeflate_alloc_decompressor(), libdeflate_free_decompressor);
  if (!decompressor) return false;
  // No actual-size argument: libdeflate then succeeds only if the stream fills the buffer exactly.
  return libdeflate_zlib_decompress(decompressor.get(), in.data(), in.size(), out.data(), out.size(), nullptr) ==
         LIBDEFLATE_SUCCESS;
}

// True if `dataset` is stored as WriteViewChunks writes it: chunks of one view ([1][1][...] over [nv][nu][...]),
// filtered by shuffle then deflate, elements of `memory_type`.
bool StoredOneViewPerChunk(hid_t dataset, hid_t memory_type, const std::vector<hsize_t>& dims) {
  const hid_t type = H5Dget_type(dataset);
  const bool same_type = type >= 0 && H5Tequal(type, memory_type) > 0;
  if (type >= 0) H5Tclose(type);
  if (!same_type || dims.size() < 3) return false;
  const hid_t properties = H5Dget_create_plist(dataset);
  if (properties < 0) return false;
  std::vector<hsize_t> chunk(dims.size(), 0);
  bool layout = H5Pget_layout(properties) == H5D_CHUNKED &&
                H5Pget_chunk(properties, static_cast<int>(chunk.size()), chunk.data()) == static_cast<int>(dims.size());
  layout = layout && chunk[0] == 1 && chunk[1] == 1 && std::equal(chunk.begin() + 2, chunk.end(), dims.begin() + 2);
  layout = layout && H5Pget_nfilters(properties) == 2;
  for (unsigned i = 0; layout && i < 2; ++i) {
    unsigned flags = 0;
    std::size_t count = 1;
    unsigned value = 0;
    const H5Z_filter_t filter = H5Pget_filter2(properties, i, &flags, &count, &value, 0, nullptr, nullptr);
    layout = filter == (i == 0 ? H5Z_FILTER_SHUFFLE : H5Z_FILTER_DEFLATE);
    // The shuffle's stored element size is what HDF5 unshuffles with; it must be the type's.
    if (i == 0) layout = layout && count == 1 && value == H5Tget_size(memory_type);
  }
  H5Pclose(properties);
  return layout;
}

}  // namespace

bool ReadViewChunks(hid_t dataset, hid_t memory_type, void* destination, std::size_t count, const std::string& name,
                    std::size_t first_view) {
  const hid_t space = H5Dget_space(dataset);
  if (space < 0) return false;
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  const bool read_dims = rank > 0 && H5Sget_simple_extent_dims(space, dims.data(), nullptr) == rank;
  H5Sclose(space);
  if (!read_dims || !StoredOneViewPerChunk(dataset, memory_type, dims)) return false;
  std::size_t chunk_elements = 1;
  for (std::size_t i = 2; i < dims.size(); ++i) chunk_elements *= static_cast<std::size_t>(dims[i]);
  const std::size_t all_views = static_cast<std::size_t>(dims[0] * dims[1]);
  const std::size_t views = count / chunk_elements;  // read: views [first_view, first_view + views)
  if (views * chunk_elements != count || first_view > all_views || views > all_views - first_view) return false;
  const std::size_t element_size = H5Tget_size(memory_type);
  const std::size_t chunk_bytes = chunk_elements * element_size;
  // HDF5's own deflate filter counts in 32 bits: larger chunks are left to it (and to its error).
  if (chunk_bytes > std::numeric_limits<std::uint32_t>::max()) return false;
  auto* bytes = static_cast<std::uint8_t*>(destination);
  hsize_t file_bytes = 0;
  const hid_t file = H5Iget_file_id(dataset);
  const bool sized = file >= 0 && H5Fget_filesize(file, &file_bytes) >= 0;
  if (file >= 0) H5Fclose(file);
  if (!sized) return false;
  hsize_t stored_total = 0;
  // Read a batch of raw chunks on one thread (HDF5 is not thread-safe), then inflate them in parallel: memory stays
  // bounded by a batch of compressed chunks, which together fit in the file.
  const std::size_t batch = 16;
  std::vector<std::vector<std::uint8_t>> raw(batch);
  for (std::size_t first = 0; first < views; first += batch) {
    const std::size_t count_in_batch = std::min(batch, views - first);
    for (std::size_t k = 0; k < count_in_batch; ++k) {
      const std::size_t camera = first_view + first + k;
      std::vector<hsize_t> offset(dims.size(), 0);
      offset[0] = static_cast<hsize_t>(camera / dims[1]);
      offset[1] = static_cast<hsize_t>(camera % dims[1]);
      hsize_t stored = 0;
      if (H5Dget_chunk_storage_size(dataset, offset.data(), &stored) < 0 || stored == 0 ||
          stored > std::numeric_limits<std::uint32_t>::max())
        return false;
      // A chunk index that lies must not size the allocations: the chunks together fit in the file.
      stored_total += stored;
      if (stored_total > file_bytes)
        ThrowFileError(name, "the chunks up to view " + std::to_string(camera) + " declare " +
                                 std::to_string(stored_total) + " bytes, more than the whole file");
      raw[k].resize(static_cast<std::size_t>(stored));
      std::uint32_t filter_mask = 0;
      if (H5Dread_chunk(dataset, H5P_DEFAULT, offset.data(), &filter_mask, raw[k].data()) < 0)
        ThrowFileError(name, "reading the chunk of view " + std::to_string(camera) + " failed");
      if (filter_mask != 0) return false;  // a filter was skipped for this chunk: HDF5's own read knows what to do
    }
    // A chunk that does not inflate is an lfsp::Error, rethrown by ParallelFor once the batch is done.
    ParallelFor(static_cast<int>(count_in_batch), [&](int k) {
      const std::size_t view = first + static_cast<std::size_t>(k);  // in the run read
      std::vector<std::uint8_t> planes(chunk_bytes);
      if (!InflateChunk(raw[static_cast<std::size_t>(k)], planes))
        ThrowFileError(name,
                       "the chunk of view " + std::to_string(first_view + view) + " does not inflate to its size");
      Unshuffle(planes.data(), chunk_elements, element_size, bytes + view * chunk_bytes);
    });
  }
  return true;
}

void WriteViewChunks(hid_t dataset, const ViewChunkSource& source, std::size_t element_size, std::size_t views, int nu,
                     std::size_t chunk_elements, int rank, int level, const std::string& name) {
  const std::size_t chunk_bytes = chunk_elements * element_size;
  // Compressed in parallel a batch at a time (bounded memory), written in order by one thread (HDF5 is not
  // thread-safe).
  const std::size_t batch = 16;
  std::vector<std::vector<std::uint8_t>> compressed(batch);
  for (std::size_t first = 0; first < views; first += batch) {
    const std::size_t count = std::min(batch, views - first);
    ParallelFor(static_cast<int>(count), [&](int k) {
      const std::size_t view = first + static_cast<std::size_t>(k);
      std::vector<std::uint8_t> chunk(chunk_bytes);
      source(view, chunk.data());
      const std::vector<std::uint8_t> shuffled = Shuffled(chunk.data(), chunk_elements, element_size);
      if (!DeflateChunk(shuffled, element_size, level, compressed[static_cast<std::size_t>(k)]))
        ThrowFileError(name, "compressing view " + std::to_string(view) + " failed");
    });
    for (std::size_t k = 0; k < count; ++k) {
      std::vector<hsize_t> offset(static_cast<std::size_t>(rank), 0);
      offset[0] = static_cast<hsize_t>((first + k) / static_cast<std::size_t>(nu));
      offset[1] = static_cast<hsize_t>((first + k) % static_cast<std::size_t>(nu));
      if (H5Dwrite_chunk(dataset, H5P_DEFAULT, 0, offset.data(), compressed[k].size(), compressed[k].data()) < 0)
        ThrowFileError(name, "HDF5 chunk write failed");
    }
  }
}

}  // namespace lfsp
