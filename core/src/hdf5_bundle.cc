#include "lfsp/core/hdf5_bundle.h"

#include "hdf5_chunks.h"
#include "hdf5_contiguous.h"
#include "hdf5_limits.h"

#include <H5Cpp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <type_traits>
#include <vector>

#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/foreign_crash_guard.h"
#include "lfsp/core/input_limits.h"
#include "lfsp/core/sample_levels.h"
#include "lfsp/core/untrusted_json.h"
#include "lfsp/core/view_crop.h"

namespace lfsp {
namespace fs = std::filesystem;

namespace {

constexpr int kFormatVersion = 1;

// The dataset's shape, after checking that reading it would not allocate more than the file can justify.
std::vector<hsize_t> Dimensions(const H5::DataSet& dataset) {
  CheckDeclaredStorage(dataset);
  const H5::DataSpace space = dataset.getSpace();
  std::vector<hsize_t> dims(static_cast<std::size_t>(space.getSimpleExtentNdims()));
  space.getSimpleExtentDims(dims.data());
  return dims;
}

std::string DimsText(const std::vector<hsize_t>& dims) {
  std::string text;
  for (std::size_t i = 0; i < dims.size(); ++i) text += (i ? "x" : "") + std::to_string(dims[i]);
  return text;
}

ViewBlock AllViews(const LightFieldShape& shape) { return {{0, 0}, shape.nu, shape.nv}; }

LightFieldShape BlockShape(LightFieldShape shape, const ViewBlock& block) {
  shape.nu = block.nu;
  shape.nv = block.nv;
  return shape;
}

// The views of a dataset [nv][nu][...] to read: the block, of a light field of `stored_nu` views per row. Each
// view's elements (the product of the dimensions past the first two) are `view_elements`.
struct ViewSelection {
  ViewBlock block;
  int stored_nu = 0;
  std::size_t view_elements = 0;
  std::size_t Elements() const { return static_cast<std::size_t>(block.nu) * block.nv * view_elements; }
};

ViewSelection SelectionOf(const H5::DataSet& dataset, const ViewBlock& block, int stored_nu) {
  const std::vector<hsize_t> dims = Dimensions(dataset);
  std::size_t view_elements = 1;
  for (std::size_t i = 2; i < dims.size(); ++i) view_elements *= static_cast<std::size_t>(dims[i]);
  return {block, stored_nu, view_elements};
}

// The block's views as runs of consecutive views in the file's order, each one hyperslab: the whole block at once
// when it is as wide as the stored light field (whole rows of views; all of the light field, read as one), else
// one run per row of views.
std::vector<ViewBlock> RunsOf(const ViewSelection& selection) {
  const ViewBlock& block = selection.block;
  if (block.nu == selection.stored_nu || block.nv == 1) return {block};
  std::vector<ViewBlock> runs;
  for (int v = 0; v < block.nv; ++v) runs.push_back({{block.first.u, block.first.v + v}, block.nu, 1});
  return runs;
}

// Reads one run of views stored exactly as `type` without HDF5's own reading: datasets of one view per chunk (what
// WriteBundle writes) are inflated in parallel, contiguous ones (the simulator's ground truth) read in parallel.
// False when the dataset is stored otherwise.
bool ReadRunDirectly(const H5::DataSet& dataset, const H5::PredType& type, void* destination, const ViewBlock& run,
                     const ViewSelection& selection, const std::string& where) {
  const std::size_t first_view = static_cast<std::size_t>(run.first.v) * selection.stored_nu + run.first.u;
  const std::size_t count = static_cast<std::size_t>(run.nu) * run.nv * selection.view_elements;
  return ReadViewChunks(dataset.getId(), type.getId(), destination, count, where, first_view) ||
         ReadContiguous(dataset.getId(), type.getId(), destination, count, where, first_view * selection.view_elements);
}

// Reads one run of views through HDF5 (any layout; HDF5 converts the stored type to `type`).
void ReadRunThroughHdf5(const H5::DataSet& dataset, const H5::PredType& type, void* destination, const ViewBlock& run) {
  H5::DataSpace file_space = dataset.getSpace();
  std::vector<hsize_t> count(static_cast<std::size_t>(file_space.getSimpleExtentNdims()));
  file_space.getSimpleExtentDims(count.data());
  std::vector<hsize_t> offset(count.size(), 0);
  offset[0] = static_cast<hsize_t>(run.first.v);
  offset[1] = static_cast<hsize_t>(run.first.u);
  count[0] = static_cast<hsize_t>(run.nv);
  count[1] = static_cast<hsize_t>(run.nu);
  file_space.selectHyperslab(H5S_SELECT_SET, count.data(), offset.data());
  const H5::DataSpace memory_space(static_cast<int>(count.size()), count.data());
  dataset.read(destination, type, memory_space, file_space);
}

// Reads the selected views of a dataset [nv][nu][...] into `destination` as `type`, in the block's view order:
// directly where the dataset's layout allows, else through HDF5.
void ReadViews(const H5::DataSet& dataset, const H5::PredType& type, void* destination, const ViewSelection& selection,
               const std::string& where) {
  auto* out = static_cast<char*>(destination);
  for (const ViewBlock& run : RunsOf(selection)) {
    if (!ReadRunDirectly(dataset, type, out, run, selection, where)) ReadRunThroughHdf5(dataset, type, out, run);
    out += static_cast<std::size_t>(run.nu) * run.nv * selection.view_elements * type.getSize();
  }
}

// Reads the selected views of a numeric dataset of any integer or float type into floats: unsigned 8/16-bit samples
// are scaled to [0, 1] (the HCI files store uint8 views), floats are taken as they are.
void ReadSamplesAsFloat(const H5::DataSet& dataset, float* destination, const ViewSelection& selection,
                        const std::string& where) {
  const std::size_t count = selection.Elements();
  const auto read = [&](void* values, const H5::PredType& type) { ReadViews(dataset, type, values, selection, where); };
  const H5T_class_t type_class = dataset.getTypeClass();
  if (type_class == H5T_FLOAT) {
    read(destination, H5::PredType::NATIVE_FLOAT);
    return;
  }
  if (type_class != H5T_INTEGER) ThrowFileError(where, "samples are neither integer nor float");
  const std::size_t size = dataset.getDataType().getSize();
  if (size == 1) {
    std::vector<std::uint8_t> raw(count);
    read(raw.data(), H5::PredType::NATIVE_UINT8);
#pragma omp parallel for
    for (std::size_t i = 0; i < count; ++i) destination[i] = static_cast<float>(raw[i]) / 255.0f;
  } else if (size == 2) {
    std::vector<std::uint16_t> raw(count);
    read(raw.data(), H5::PredType::NATIVE_UINT16);
#pragma omp parallel for
    for (std::size_t i = 0; i < count; ++i) destination[i] = static_cast<float>(raw[i]) / 65535.0f;
  } else {
    ThrowFileError(where, "unsupported integer sample size of " + std::to_string(size) + " bytes");
  }
}

// A string attribute. A fixed-length one is read into a buffer sized from the very datatype H5Aread writes with:
// H5::Attribute's own string reader sizes its buffer from the native type instead, and a corrupt file can make the
// two disagree (make fuzz found H5Aread writing 4 bytes into its 2-byte buffer).
std::string ReadStringAttribute(const H5::H5Object& object, const char* name) {
  if (!object.attrExists(name)) return "";
  const H5::Attribute attribute = object.openAttribute(name);
  const H5::StrType type = attribute.getStrType();
  if (type.isVariableStr()) {
    std::string value;
    attribute.read(type, value);
    return value;
  }
  if (attribute.getSpace().getSimpleExtentNpoints() != 1)
    throw H5::AttributeIException("ReadStringAttribute", std::string("attribute '") + name + "' is not one string");
  constexpr std::size_t kLongestString = std::size_t{1} << 28;  // metadata JSON is kilobytes
  const std::size_t bytes = type.getSize();
  if (bytes == 0 || bytes > kLongestString)
    throw H5::AttributeIException("ReadStringAttribute", std::string("attribute '") + name + "' declares a string of " +
                                                             std::to_string(bytes) + " bytes");
  std::string value(bytes, '\0');
  attribute.read(type, value.data());
  value.resize(value.find('\0') == std::string::npos ? bytes : value.find('\0'));  // null-padded strings
  return value;
}

std::optional<double> ReadNumberAttribute(const H5::H5Object& object, const char* name) {
  if (!object.attrExists(name)) return std::nullopt;
  const H5::Attribute attribute = object.openAttribute(name);
  if (attribute.getTypeClass() != H5T_FLOAT && attribute.getTypeClass() != H5T_INTEGER) return std::nullopt;
  if (attribute.getSpace().getSimpleExtentNpoints() != 1) return std::nullopt;
  double value = 0.0;
  attribute.read(H5::PredType::NATIVE_DOUBLE, &value);
  return value;
}

void WriteStringAttribute(H5::H5Object& object, const char* name, const std::string& value) {
  const H5::StrType type(H5::PredType::C_S1, std::max<std::size_t>(value.size(), 1));
  H5::Attribute attribute = object.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
  attribute.write(type, value);
}

// The file format of a new bundle: the oldest (which every HDF5 reads, and whose bytes the tests pin) unless the
// metadata attribute is too large for it. The oldest format keeps attributes in the object header, at most 64 KiB;
// a scene of 200,000 objects carried 60 MB of metadata and H5Acreate2 failed. From HDF5 1.8 on, large attributes
// go to dense storage.
H5::FileAccPropList AccessFor(const std::string& metadata) {
  constexpr std::size_t kLargestCompactAttribute = 60000;  // under 64 KiB with the header message's own bytes
  H5::FileAccPropList access;
  if (metadata.size() > kLargestCompactAttribute)
    H5Pset_libver_bounds(access.getId(), H5F_LIBVER_V18, H5F_LIBVER_LATEST);
  return access;
}

// The light field's shape as dataset LF declares it (channels: 1..3, a 4th is dropped on reading).
LightFieldShape StoredShape(const H5::DataSet& dataset, const std::string& name) {
  const std::vector<hsize_t> dims = Dimensions(dataset);
  if (dims.size() != 5 || dims[4] < 1 || dims[4] > 4)
    ThrowFileError(name, "dataset LF has shape " + DimsText(dims) + ", expected nv x nu x H x W x C (C = 1..4)");
  for (hsize_t dim : dims)
    if (dim == 0 || dim > 65536) ThrowFileError(name, "dataset LF has an implausible shape " + DimsText(dims));
  LightFieldShape shape;
  shape.nv = static_cast<int>(dims[0]);
  shape.nu = static_cast<int>(dims[1]);
  shape.height = static_cast<int>(dims[2]);
  shape.width = static_cast<int>(dims[3]);
  shape.channels = static_cast<int>(std::min<hsize_t>(dims[4], 3));
  return shape;
}

// The block's views of dataset LF, whose light field has the shape `stored`.
LightField ReadLightFieldDataset(const H5::DataSet& dataset, const LightFieldShape& stored, const ViewBlock& block,
                                 const std::string& name) {
  const std::vector<hsize_t> dims = Dimensions(dataset);
  const LightFieldShape shape = BlockShape(stored, block);
  // Samples become float32 in memory (all of RGBA while the alpha channel is dropped).
  CheckDeclaredAllocation(
      name + ": dataset LF",
      SaturatingBytes({static_cast<hsize_t>(block.nv), static_cast<hsize_t>(block.nu), dims[2], dims[3], dims[4]},
                      sizeof(float)),
      FileBytes(name));
  const ViewSelection selection = SelectionOf(dataset, block, stored.nu);
  LightField light_field(shape);
  if (static_cast<int>(dims[4]) == shape.channels) {
    ReadSamplesAsFloat(dataset, light_field.data(), selection, name + ": LF");
  } else {  // RGBA: drop the alpha channel
    std::vector<float> all(shape.TotalSamples() / 3 * 4);
    ReadSamplesAsFloat(dataset, all.data(), selection, name + ": LF");
    for (std::size_t i = 0, n = all.size() / 4; i < n; ++i) std::copy_n(&all[i * 4], 3, light_field.data() + i * 3);
  }
  return light_field;
}

void CheckSpatialMatch(const std::vector<hsize_t>& dims, const LightFieldShape& shape, const std::string& where) {
  if (dims.size() < 2 || dims[dims.size() - 2] != static_cast<hsize_t>(shape.height) ||
      dims[dims.size() - 1] != static_cast<hsize_t>(shape.width))
    ThrowFileError(where,
                   "has shape " + DimsText(dims) + ", which does not match the light field (" + ToString(shape) + ")");
}

DisparityMap ReadDisparityDataset(const H5::H5File& file, const LightFieldShape& shape, const std::string& name) {
  const H5::DataSet dataset = file.openDataSet("disparity");
  const std::vector<hsize_t> dims = Dimensions(dataset);
  if (dims.size() != 2) ThrowFileError(name, "dataset disparity has shape " + DimsText(dims) + ", expected H x W");
  CheckSpatialMatch(dims, shape, name + ": dataset disparity");
  DisparityMap disparity(shape.width, shape.height);
  dataset.read(disparity.data(), H5::PredType::NATIVE_FLOAT);
  return disparity;
}

// Widens `count` 16-bit labels, read into the start of the labels' own storage, over the whole of it in place: no
// buffer of 16-bit labels beside the labels at the decode stage's peak of memory. Label i is written over bytes
// [4i, 4i + 4), where the 16-bit labels 2i and 2i + 1 lie, so the upper half is widened first (its writes land past
// every 16-bit label), then the upper half of what is left, and so on: a round's writes land on labels earlier
// rounds widened, never on the 16-bit labels it or a later round reads, so each round runs on every core.
template <typename Narrow>
void WidenInPlace(std::int32_t* values, std::size_t count) {
  const auto* narrow = reinterpret_cast<const unsigned char*>(values);
  const auto widen = [values, narrow](std::size_t i) {
    Narrow value;
    std::memcpy(&value, narrow + i * sizeof(Narrow), sizeof(Narrow));
    values[i] = value;
  };
  std::size_t end = count;
  while (end > 4096) {
    const std::size_t begin = (end + 1) / 2;  // 2 begin >= end: this round's writes start past its reads
#pragma omp parallel for
    for (std::size_t i = begin; i < end; ++i) widen(i);
    end = begin;
  }
  for (std::size_t i = end; i-- > 0;) widen(i);  // downwards, each label read before its bytes are written
}

// The selected labels of a 16-bit dataset (what WriteBundle and the simulator store) as they are stored, through
// ReadViewChunks or ReadContiguous (in parallel), then widened in place: HDF5's conversion to int32 runs on one
// thread, and the labels were filled before it wrote them (the simulator's 15x15 ground truth holds 60 M labels).
// Empty when the dataset is stored otherwise (HDF5 then reads it).
template <typename Narrow>
std::optional<Labels> ReadNarrowLabels(const H5::DataSet& dataset, const H5::PredType& type,
                                       const LightFieldShape& shape, const ViewSelection& selection,
                                       const std::string& where) {
  Labels labels(shape, Labels::Unfilled{});
  auto* narrow = reinterpret_cast<unsigned char*>(labels.data());  // the runs, one after another, as stored
  for (const ViewBlock& run : RunsOf(selection)) {
    if (!ReadRunDirectly(dataset, type, narrow, run, selection, where)) return std::nullopt;
    narrow += static_cast<std::size_t>(run.nu) * run.nv * selection.view_elements * sizeof(Narrow);
  }
  WidenInPlace<Narrow>(labels.data(), labels.size());
  return labels;
}

std::optional<Labels> ReadSixteenBitLabels(const H5::DataSet& dataset, const LightFieldShape& shape,
                                           const ViewSelection& selection, const std::string& where) {
  const H5::IntType type = dataset.getIntType();
  if (type.getSize() != 2) return std::nullopt;
  if (type.getSign() == H5T_SGN_NONE)  // never below kUnlabelled
    return ReadNarrowLabels<std::uint16_t>(dataset, H5::PredType::NATIVE_UINT16, shape, selection, where);
  std::optional<Labels> labels =
      ReadNarrowLabels<std::int16_t>(dataset, H5::PredType::NATIVE_INT16, shape, selection, where);
  if (labels) RequireValidLabelValues(*labels, where);
  return labels;
}

// The block's labels of a light field of the shape `stored`: the dataset holds nv x nu x H x W labels, or H x W
// for the centre view only (the other views then stay unlabelled, and all views when the block leaves the centre
// out).
Labels ReadLabelsDataset(const H5::H5File& file, const char* dataset_name, const LightFieldShape& stored,
                         const ViewBlock& block, const std::string& name) {
  const H5::DataSet dataset = file.openDataSet(dataset_name);
  const std::vector<hsize_t> dims = Dimensions(dataset);
  const std::string where = name + ": dataset " + dataset_name;
  if (dataset.getTypeClass() != H5T_INTEGER) ThrowFileError(where, "does not hold integers");
  CheckSpatialMatch(dims, stored, where);
  const LightFieldShape shape = BlockShape(stored, block);
  if (dims.size() == 4) {
    if (dims[0] != static_cast<hsize_t>(stored.nv) || dims[1] != static_cast<hsize_t>(stored.nu))
      ThrowFileError(where, "has " + DimsText(dims) + " but the light field has " + ToString(stored));
    const ViewSelection selection = SelectionOf(dataset, block, stored.nu);
    if (std::optional<Labels> sixteen = ReadSixteenBitLabels(dataset, shape, selection, where))
      return std::move(*sixteen);
    Labels labels(shape);
    ReadViews(dataset, H5::PredType::NATIVE_INT32, labels.data(), selection, where);
    RequireValidLabelValues(labels, where);
    return labels;
  }
  Labels labels(shape);
  const ViewIndex centre = stored.Centre();
  const ViewIndex in_block{centre.u - block.first.u, centre.v - block.first.v};
  if (dims.size() == 2) {
    if (shape.Contains(in_block)) dataset.read(labels.ViewData(in_block), H5::PredType::NATIVE_INT32);
  } else {
    ThrowFileError(where, "has shape " + DimsText(dims) + ", expected nv x nu x H x W or H x W");
  }
  RequireValidLabelValues(labels, where);
  return labels;
}

// Old HCI dataset (Wanner et al. 2013): GT_DEPTH holds depth per view; disparity = dH * focalLength / depth - shift.
std::optional<DisparityMap> ReadOldHciDisparity(const H5::H5File& file, const LightFieldShape& shape,
                                                const std::string& name) {
  if (!file.nameExists("GT_DEPTH")) return std::nullopt;
  const auto dh = ReadNumberAttribute(file, "dH");
  const auto focal = ReadNumberAttribute(file, "focalLength");
  const auto shift = ReadNumberAttribute(file, "shift");
  if (!dh || !focal || !shift)
    ThrowFileError(name, "GT_DEPTH present but the attributes dH, focalLength, shift needed to convert it are not");
  const H5::DataSet dataset = file.openDataSet("GT_DEPTH");
  const std::vector<hsize_t> dims = Dimensions(dataset);
  CheckSpatialMatch(dims, shape, name + ": dataset GT_DEPTH");
  if (dims.size() == 4 && (dims[0] != static_cast<hsize_t>(shape.nv) || dims[1] != static_cast<hsize_t>(shape.nu)))
    ThrowFileError(name,
                   "dataset GT_DEPTH has shape " + DimsText(dims) + " but the light field has " + ToString(shape));
  std::vector<float> depth(dims.size() == 4 ? shape.Views() * shape.ViewPixels() : shape.ViewPixels());
  if (dims.size() != 4 && dims.size() != 2) ThrowFileError(name, "GT_DEPTH has shape " + DimsText(dims));
  dataset.read(depth.data(), H5::PredType::NATIVE_FLOAT);
  const std::size_t centre_offset =
      dims.size() == 4 ? static_cast<std::size_t>(CameraNumber(shape.Centre(), shape.nu)) * shape.ViewPixels() : 0;
  DisparityMap disparity(shape.width, shape.height);
  for (std::size_t i = 0; i < shape.ViewPixels(); ++i) {
    const double z = depth[centre_offset + i];
    disparity.data()[i] = static_cast<float>(z > 0.0 ? *dh * *focal / z - *shift : NAN);
  }
  return disparity;
}

// HDF5 stamps objects with their creation time by default; without the stamps the same content gives the same
// bytes, so regenerated samples and outputs are byte-identical.
H5::DSetCreatPropList Untimed() {
  H5::DSetCreatPropList properties;
  H5Pset_obj_track_times(properties.getId(), false);
  return properties;
}

H5::DSetCreatPropList ChunkedPerView(const std::vector<hsize_t>& dims, int compression_level) {
  H5::DSetCreatPropList properties = Untimed();
  if (compression_level > 0) {
    std::vector<hsize_t> chunk = dims;
    chunk[0] = 1;
    chunk[1] = 1;
    properties.setChunk(static_cast<int>(chunk.size()), chunk.data());
    properties.setShuffle();  // byte planes first: samples and labels compress far better
    properties.setDeflate(std::min(compression_level, 9));
  }
  return properties;
}

// Refuses a path that is not an HDF5 file with a one-line error, before the HDF5 library would print its own.
void RequireHdf5File(const fs::path& path) {
  const std::string name = path.string();
  RequireRegularFile(path);
  H5::Exception::dontPrint();
  if (H5Fis_hdf5(name.c_str()) <= 0) ThrowFileError(name, "not an HDF5 file");
}

// Opens the HDF5 file `path` read-only, under libhdf5's crash guard, and returns read(file, name): what the library
// throws becomes a one-line error naming the file.
template <typename Read>
auto ReadFromHdf5File(const fs::path& path, Read read) {
  const std::string name = path.string();
  RequireHdf5File(path);
  try {
    const ForeignCrashGuard guard(name, "libhdf5");
    const H5::H5File file(name, H5F_ACC_RDONLY);
    return read(file, name);
  } catch (const H5::Exception& error) {
    ThrowFileError(name, "HDF5 read failed in " + error.getFuncName() + ": " + error.getDetailMsg());
  }
}

}  // namespace

namespace {

// The views `block` names must lie inside `shape`'s (lfsp::Error naming `where` otherwise).
void RequireBlockInside(const ViewBlock& block, const LightFieldShape& shape, const std::string& where) {
  if (block.nu < 1 || block.nv < 1 || block.first.u < 0 || block.first.v < 0 || block.first.u > shape.nu - block.nu ||
      block.first.v > shape.nv - block.nv)
    throw Error(where + ": the " + std::to_string(block.nu) + " x " + std::to_string(block.nv) + " views from view (" +
                std::to_string(block.first.u) + ", " + std::to_string(block.first.v) + ") are not all among the " +
                std::to_string(shape.nu) + " x " + std::to_string(shape.nv) + " views of " + ToString(shape));
}

// The bundle's weights dataset, checked against the samples' shape; nothing when the bundle has none.
std::optional<H5::DataSet> OpenWeights(const H5::H5File& file, const LightFieldShape& stored, const std::string& name) {
  if (!file.nameExists("weights")) return std::nullopt;
  H5::DataSet dataset = file.openDataSet("weights");
  const std::vector<hsize_t> dims = Dimensions(dataset);
  if (dims.size() != 4 || dims[0] != static_cast<hsize_t>(stored.nv) || dims[1] != static_cast<hsize_t>(stored.nu))
    ThrowFileError(name, "dataset weights has shape " + DimsText(dims) + ", expected nv x nu x H x W");
  CheckSpatialMatch(dims, stored, name + ": dataset weights");
  return dataset;
}

// The block's views of the samples, with the transfer and metadata, and their weights if `parts` asks for them.
LightField ReadLightFieldWithWeights(const H5::H5File& file, const H5::DataSet& samples, const LightFieldShape& stored,
                                     const ViewBlock& block, const BundleParts& parts, const std::string& name) {
  LightField light_field = ReadLightFieldDataset(samples, stored, block, name);
  const std::string transfer = ReadStringAttribute(file, "transfer");
  light_field.transfer = transfer.empty() ? Transfer::kSrgb : TransferFromFile(transfer, name, "attribute transfer");
  const std::string metadata = ReadStringAttribute(file, "metadata");
  if (!metadata.empty()) {
    light_field.metadata = ParseUntrustedJsonObject(metadata, name + ": attribute 'metadata'");
  }
  if (!parts.weights) return light_field;
  const std::optional<H5::DataSet> dataset = OpenWeights(file, stored, name);
  if (!dataset) return light_field;
  light_field.EnableWeights();
  ReadSamplesAsFloat(*dataset, light_field.weights().data(), SelectionOf(*dataset, block, stored.nu),
                     name + ": weights");
  return light_field;
}

}  // namespace

Bundle ReadBundle(const fs::path& path) { return ReadBundle(path, BundleParts{}); }

Bundle ReadBundle(const fs::path& path, const BundleParts& parts) {
  return ReadFromHdf5File(path, [&path, &parts](const H5::H5File& file, const std::string& name) {
    if (!file.nameExists("LF")) ThrowFileError(name, "no dataset 'LF': not a light-field bundle");
    const H5::DataSet samples = file.openDataSet("LF");
    const LightFieldShape stored = StoredShape(samples, name);
    const ViewBlock block = parts.views.value_or(AllViews(stored));
    RequireBlockInside(block, stored, name);
    Bundle bundle;
    if (parts.samples) bundle.light_field = ReadLightFieldWithWeights(file, samples, stored, block, parts, name);
    if (parts.disparity) {
      if (file.nameExists("disparity")) {
        bundle.disparity = ReadDisparityDataset(file, stored, name);
      } else {
        bundle.disparity = ReadOldHciDisparity(file, stored, name);
      }
    }
    if (!parts.labels) return bundle;
    if (file.nameExists("labels")) bundle.labels = ReadLabelsDataset(file, "labels", stored, block, name);

    // Old HCI layout: ground-truth labels live in a sibling labels.h5.
    const fs::path sibling_labels = path.parent_path() / "labels.h5";
    std::error_code exists_error;
    if (!bundle.labels && fs::exists(sibling_labels, exists_error) && sibling_labels.filename() != path.filename()) {
      // Its problems are named with its own path (one that was not HDF5 was "lf.h5: HDF5 read failed in H5File
      // constructor").
      const std::string labels_name = sibling_labels.string();
      RequireHdf5File(sibling_labels);
      try {
        const H5::H5File labels_file(labels_name, H5F_ACC_RDONLY);
        if (labels_file.nameExists("GT_LABELS"))
          bundle.labels = ReadLabelsDataset(labels_file, "GT_LABELS", stored, block, labels_name);
      } catch (const H5::Exception& error) {
        ThrowFileError(labels_name, "HDF5 read failed in " + error.getFuncName() + ": " + error.getDetailMsg());
      }
    }
    return bundle;
  });
}

LightFieldShape ReadBundleShape(const fs::path& path) {
  return ReadFromHdf5File(path, [](const H5::H5File& file, const std::string& name) {
    if (!file.nameExists("LF")) ThrowFileError(name, "no dataset 'LF': not a light-field bundle");
    return StoredShape(file.openDataSet("LF"), name);
  });
}

std::vector<double> ReadViewMeanWeights(const fs::path& path) {
  return ReadFromHdf5File(path, [](const H5::H5File& file, const std::string& name) {
    if (!file.nameExists("LF")) ThrowFileError(name, "no dataset 'LF': not a light-field bundle");
    const LightFieldShape stored = StoredShape(file.openDataSet("LF"), name);
    std::vector<double> means;
    const std::optional<H5::DataSet> dataset = OpenWeights(file, stored, name);
    if (!dataset) return means;
    const std::size_t view_pixels = stored.ViewPixels();
    std::vector<float> row(static_cast<std::size_t>(stored.nu) * view_pixels);
    for (int v = 0; v < stored.nv; ++v) {
      const ViewBlock block{{0, v}, stored.nu, 1};
      ReadSamplesAsFloat(*dataset, row.data(), SelectionOf(*dataset, block, stored.nu), name + ": weights");
      for (int u = 0; u < stored.nu; ++u)
        means.push_back(MeanOfWeights(row.data() + static_cast<std::size_t>(u) * view_pixels, view_pixels));
    }
    return means;
  });
}

Labels ReadLabels(const fs::path& path) {
  return ReadFromHdf5File(path, [&path](const H5::H5File& file, const std::string& name) {
    const char* dataset_name = file.nameExists("labels")      ? "labels"
                               : file.nameExists("GT_LABELS") ? "GT_LABELS"
                                                              : nullptr;
    if (dataset_name == nullptr) ThrowFileError(name, "has neither a 'labels' nor a 'GT_LABELS' dataset");
    const std::vector<hsize_t> dims = Dimensions(file.openDataSet(dataset_name));
    const std::string where = name + ": dataset " + dataset_name;
    if (dims.size() != 4) ThrowFileError(where, "has shape " + DimsText(dims) + ", expected nv x nu x H x W");
    for (const hsize_t dim : dims)
      if (dim == 0 || dim > 65536) ThrowFileError(where, "has an implausible shape " + DimsText(dims));
    CheckDeclaredAllocation(where, SaturatingBytes({dims[0], dims[1], dims[2], dims[3]}, sizeof(std::int32_t)),
                            FileBytes(path));
    const LightFieldShape shape{static_cast<int>(dims[1]), static_cast<int>(dims[0]), static_cast<int>(dims[3]),
                                static_cast<int>(dims[2]), 1};
    return ReadLabelsDataset(file, dataset_name, shape, AllViews(shape), name);
  });
}

namespace {

// Whether every value comes back bit for bit from the integer level WriteBundle stores it as (SampleLevel) and the
// float ReadBundle makes of that level (level / full_scale): then that integer type holds the values losslessly.
// NaN, values outside [0, 1] and -0 are not exact.
bool ExactAtLevels(const float* values, std::size_t count, float full_scale) {
  std::size_t inexact = 0;
#pragma omp parallel for schedule(static) reduction(+ : inexact)
  for (std::size_t i = 0; i < count; ++i) {
    const float back = static_cast<float>(SampleLevel(values[i], full_scale)) / full_scale;
    inexact += std::bit_cast<std::uint32_t>(back) != std::bit_cast<std::uint32_t>(values[i]) ? 1 : 0;
  }
  return inexact == 0;
}

}  // namespace

BundleWriteOptions CompactBundleOptions(const LightField& light_field) {
  constexpr int kLevel = 1;
  if (DecodedFromSensor(light_field)) return {SampleStorage::kUint16, kLevel};
  // Views read from 8- or 16-bit images hold exact levels: stored as such, a quarter or half of float32's bytes to
  // deflate (HCI antinous's 9x9 views: segmentation.h5's LF took 0.96 s to write as float32). 16-bit samples take
  // 16-bit weights beside them (WriteBundle), so those must be exact too; 8-bit samples keep float32 weights.
  if (ExactAtLevels(light_field.data(), light_field.size(), 255.0f)) return {SampleStorage::kUint8, kLevel};
  if (ExactAtLevels(light_field.data(), light_field.size(), 65535.0f) &&
      (!light_field.HasWeights() ||
       ExactAtLevels(light_field.weights().data(), light_field.weights().size(), 65535.0f)))
    return {SampleStorage::kUint16, kLevel};
  return {SampleStorage::kFloat32, kLevel};
}

void RoundToStoredPrecision(LightField& light_field, SampleStorage storage) {
  if (storage == SampleStorage::kFloat32) return;
  const float scale = storage == SampleStorage::kUint16 ? 65535.0f : 255.0f;
  const auto round = [scale](float* values, std::size_t count) {
#pragma omp parallel for
    for (std::size_t i = 0; i < count; ++i) values[i] = static_cast<float>(SampleLevel(values[i], scale)) / scale;
  };
  round(light_field.data(), light_field.size());
  // Weights are stored as 16-bit only beside 16-bit samples (else as float32).
  if (light_field.HasWeights() && storage == SampleStorage::kUint16)
    round(light_field.weights().data(), light_field.weights().size());
}

void WriteBundle(const Bundle& bundle, const fs::path& path, const BundleWriteOptions& options) {
  const std::string name = path.string();
  const LightField& light_field = bundle.light_field;
  const LightFieldShape& shape = light_field.shape();
  if (light_field.empty()) ThrowFileError(name, "refusing to write an empty light field");
  H5::Exception::dontPrint();
  AtomicOutput output(path);
  try {
    H5::FileCreatPropList file_properties;
    H5Pset_obj_track_times(file_properties.getId(), false);
    const std::string metadata = light_field.metadata.dump();
    H5::H5File file(output.temporary().string(), H5F_ACC_TRUNC, file_properties, AccessFor(metadata));
    const std::vector<hsize_t> lf_dims = {static_cast<hsize_t>(shape.nv), static_cast<hsize_t>(shape.nu),
                                          static_cast<hsize_t>(shape.height), static_cast<hsize_t>(shape.width),
                                          static_cast<hsize_t>(shape.channels)};
    const H5::DataSpace lf_space(5, lf_dims.data());
    const H5::DSetCreatPropList lf_properties = ChunkedPerView(lf_dims, options.compression_level);
    const std::size_t views = static_cast<std::size_t>(shape.nu) * static_cast<std::size_t>(shape.nv);
    // `views` x `chunk_elements` values, stored as Stored (each through `convert`), one view per chunk. Compressed:
    // a batch of views at a time, converted as they are compressed in parallel (WriteViewChunks), so no converted
    // copy of the whole is held (a full Illum decode's uint16 samples: 363 MB). Uncompressed: in one call.
    auto write = [&]<typename Stored, typename Value, typename Convert>(
                     H5::DataSet& dataset, const Value* values, const H5::PredType& memory, std::size_t chunk_elements,
                     int rank, Convert convert) {
      if (options.compression_level > 0) {
        const auto source = [&](std::size_t view, std::uint8_t* chunk) {
          const Value* in = values + view * chunk_elements;
          for (std::size_t i = 0; i < chunk_elements; ++i) {
            const Stored stored = convert(in[i]);
            std::memcpy(chunk + i * sizeof(Stored), &stored, sizeof(Stored));
          }
        };
        WriteViewChunks(dataset.getId(), source, sizeof(Stored), views, shape.nu, chunk_elements, rank,
                        std::min(options.compression_level, 9), name);
      } else if constexpr (std::is_same_v<Stored, Value>) {
        dataset.write(values, memory);
      } else {
        std::vector<Stored> converted(views * chunk_elements);
#pragma omp parallel for
        for (std::size_t i = 0; i < converted.size(); ++i) converted[i] = convert(values[i]);
        dataset.write(converted.data(), memory);
      }
    };
    const auto as_is = [](auto value) { return value; };
    const auto level16 = [](float value) { return static_cast<std::uint16_t>(SampleLevel(value, 65535.0f)); };
    const auto level8 = [](float value) { return static_cast<std::uint8_t>(SampleLevel(value, 255.0f)); };
    const std::size_t view_samples = shape.ViewSamples();
    switch (options.storage) {
      case SampleStorage::kFloat32: {
        H5::DataSet dataset = file.createDataSet("LF", H5::PredType::IEEE_F32LE, lf_space, lf_properties);
        write.operator()<float>(dataset, light_field.data(), H5::PredType::NATIVE_FLOAT, view_samples, 5, as_is);
        break;
      }
      case SampleStorage::kUint16: {
        H5::DataSet dataset = file.createDataSet("LF", H5::PredType::STD_U16LE, lf_space, lf_properties);
        write.operator()<std::uint16_t>(dataset, light_field.data(), H5::PredType::NATIVE_UINT16, view_samples, 5,
                                        level16);
        break;
      }
      case SampleStorage::kUint8: {
        H5::DataSet dataset = file.createDataSet("LF", H5::PredType::STD_U8LE, lf_space, lf_properties);
        write.operator()<std::uint8_t>(dataset, light_field.data(), H5::PredType::NATIVE_UINT8, view_samples, 5,
                                       level8);
        break;
      }
    }
    WriteStringAttribute(file, "transfer", ToString(light_field.transfer));
    WriteStringAttribute(file, "metadata", metadata);
    H5::Attribute version =
        file.createAttribute("lfsp_format_version", H5::PredType::STD_I32LE, H5::DataSpace(H5S_SCALAR));
    version.write(H5::PredType::NATIVE_INT, &kFormatVersion);

    const std::vector<hsize_t> ray_dims(lf_dims.begin(), lf_dims.begin() + 4);
    if (light_field.HasWeights()) {
      // 16-bit like the samples when they are (weights lie in [0, 1]); float32 otherwise.
      const bool sixteen = options.storage == SampleStorage::kUint16;
      H5::DataSet dataset =
          file.createDataSet("weights", sixteen ? H5::PredType::STD_U16LE : H5::PredType::IEEE_F32LE,
                             H5::DataSpace(4, ray_dims.data()), ChunkedPerView(ray_dims, options.compression_level));
      const Array4D<float>& weights = light_field.weights();
      if (sixteen)
        write.operator()<std::uint16_t>(dataset, weights.data(), H5::PredType::NATIVE_UINT16, shape.ViewPixels(), 4,
                                        level16);
      else
        write.operator()<float>(dataset, weights.data(), H5::PredType::NATIVE_FLOAT, shape.ViewPixels(), 4, as_is);
    }
    if (bundle.disparity) {
      const DisparityMap& disparity = *bundle.disparity;
      if (disparity.width() != shape.width || disparity.height() != shape.height)
        ThrowFileError(name, "disparity map size does not match the light field");
      const hsize_t dims[2] = {static_cast<hsize_t>(disparity.height()), static_cast<hsize_t>(disparity.width())};
      H5::DataSet dataset =
          file.createDataSet("disparity", H5::PredType::IEEE_F32LE, H5::DataSpace(2, dims), Untimed());
      dataset.write(disparity.data(), H5::PredType::NATIVE_FLOAT);
    }
    if (bundle.labels) {
      if (!(bundle.labels->shape().nu == shape.nu && bundle.labels->shape().nv == shape.nv &&
            bundle.labels->shape().width == shape.width && bundle.labels->shape().height == shape.height))
        ThrowFileError(name, "labels shape does not match the light field");
      // Stored as the smallest integer type that holds them (HDF5 converts back to int32 on reading).
      const auto [lowest, highest] =
          std::minmax_element(bundle.labels->data(), bundle.labels->data() + bundle.labels->size());
      const std::int32_t* labels = bundle.labels->data();
      const bool unsigned16 = *lowest >= 0 && *highest <= 65535;
      const bool signed16 = !unsigned16 && *lowest >= -32768 && *highest <= 32767;
      const H5::PredType& stored =
          unsigned16 ? H5::PredType::STD_U16LE : (signed16 ? H5::PredType::STD_I16LE : H5::PredType::STD_I32LE);
      H5::DataSet dataset = file.createDataSet("labels", stored, H5::DataSpace(4, ray_dims.data()),
                                               ChunkedPerView(ray_dims, options.compression_level));
      const auto narrow16 = [](std::int32_t label) { return static_cast<std::uint16_t>(label); };
      const auto signed_narrow16 = [](std::int32_t label) { return static_cast<std::int16_t>(label); };
      if (options.compression_level > 0 && unsigned16)
        write.operator()<std::uint16_t>(dataset, labels, H5::PredType::NATIVE_UINT16, shape.ViewPixels(), 4, narrow16);
      else if (options.compression_level > 0 && signed16)
        write.operator()<std::int16_t>(dataset, labels, H5::PredType::NATIVE_INT16, shape.ViewPixels(), 4,
                                       signed_narrow16);
      else
        write.operator()<std::int32_t>(dataset, labels, H5::PredType::NATIVE_INT32, shape.ViewPixels(), 4, as_is);
    }
    file.close();
  } catch (const H5::Exception& error) {
    ThrowFileError(name, "HDF5 write failed in " + error.getFuncName() + ": " + error.getDetailMsg());
  }
  output.Commit();
}

}  // namespace lfsp
