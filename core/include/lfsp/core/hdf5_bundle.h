#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "lfsp/core/light_field.h"

namespace lfsp {

// Everything lfsp keeps about one light field, as stored in an HDF5 bundle (.h5):
//   LF          nv x nu x H x W x C  (float32, or uint8/uint16 scaled to [0, 1] on read)
//   weights     nv x nu x H x W      (float32, optional)
//   disparity   H x W                (float32, centre view, optional)
//   labels      nv x nu x H x W      (int32, optional)
//   attributes  transfer ("linear"/"srgb"), metadata (JSON text), and the HCI extrinsics as numbers.
struct Bundle {
  LightField light_field;
  std::optional<DisparityMap> disparity;
  std::optional<Labels> labels;
};

enum class SampleStorage { kFloat32, kUint16, kUint8 };

struct BundleWriteOptions {
  SampleStorage storage = SampleStorage::kFloat32;  // uint formats quantise: exact only for 8/16-bit data
  int compression_level = 0;                        // gzip level 0-9 (with byte shuffling); 0 keeps loading fastest
};

// What the commands write (decode, segment, recolor, pipeline): chunked by view, byte-shuffled and gzip-compressed
// at level 1 (fast); samples as 16-bit when the light field was decoded from a sensor (10- or 12-bit data: a step
// of 1.5e-5 loses nothing measurable), else losslessly: as 8- or 16-bit when every sample (and, for 16-bit, every
// weight) reads back bit for bit from its level, as views read from 8- or 16-bit images do, else as float32.
BundleWriteOptions CompactBundleOptions(const LightField& light_field);

// Rounds the samples (and weights, when they are stored alike) to the precision `storage` keeps, exactly as
// WriteBundle then ReadBundle would give them back: a run that goes on in memory then computes what a run from the
// written file computes (`lfsp pipeline` against the single commands).
void RoundToStoredPrecision(LightField& light_field, SampleStorage storage);

// Reads an lfsp bundle, or the old HCI dataset layout: lf.h5 with LF (uint8/float, nv x nu x H x W x 3) and
// GT_DEPTH (depth per view, converted to centre-view disparity with the file's dH/focalLength/shift attributes),
// plus a sibling labels.h5 with GT_LABELS when present.
Bundle ReadBundle(const std::filesystem::path& path);

// What ReadBundle reads of a bundle. A part of a large bundle costs only its own memory: the pipeline compares a
// decode with the simulator's 1 GB ideal light field one row of views at a time (issue 46).
struct BundleParts {
  // Only these views of the samples, weights and labels (a light field of the block's shape, its views in their
  // order); the disparity stays the whole light field's centre view's. All views when empty.
  std::optional<ViewBlock> views;
  bool samples = true;  // false: the light field stays empty (no samples, weights, transfer or metadata)
  bool weights = true;
  bool disparity = true;
  bool labels = true;
};
Bundle ReadBundle(const std::filesystem::path& path, const BundleParts& parts);

// The shape of a bundle's light field (its dataset LF), without reading it.
LightFieldShape ReadBundleShape(const std::filesystem::path& path);

// The mean weight of every view of a bundle (MeanOfWeights; camera order, v * nu + u), from its weights read a row of
// views at a time, without its samples: what choosing the views to process needs (LoadCentralViews). Empty when the
// bundle has no weights.
std::vector<double> ReadViewMeanWeights(const std::filesystem::path& path);

// Reads only the per-ray labels of an HDF5 file, without its light field: dataset `labels` (an lfsp bundle, as
// `lfsp segment` writes it) or `GT_LABELS` (the old HCI layout), nv x nu x H x W of any integer type. Throws
// lfsp::Error naming the file if it is missing, not HDF5, has neither dataset or the wrong rank.
Labels ReadLabels(const std::filesystem::path& path);

// Writes through a temporary file renamed when complete.
void WriteBundle(const Bundle& bundle, const std::filesystem::path& path, const BundleWriteOptions& options = {});

}  // namespace lfsp
