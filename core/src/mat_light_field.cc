#include "lfsp/core/mat_light_field.h"

#include <H5Cpp.h>
#include <matio.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "hdf5_limits.h"
#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/foreign_crash_guard.h"
#include "lfsp/core/input_limits.h"
#include "lfsp/core/sample_levels.h"
#include "mat5_structure.h"

namespace lfsp {
namespace fs = std::filesystem;

namespace {

constexpr const char* kVariable = "LF";

// MATLAB dims (nv, nu, H, W, C) as a shape; throws naming the file unless they describe a light field.
LightFieldShape ShapeFromMatlabDims(const std::vector<std::uint64_t>& dims, const std::string& name) {
  std::string text;
  for (std::uint64_t d : dims) text += (text.empty() ? "" : "x") + std::to_string(d);
  if (dims.size() != 5) ThrowFileError(name, "variable LF is " + text + "; expected 5 dimensions LF(v, u, y, x, c)");
  for (std::uint64_t d : dims)
    if (d == 0 || d > 65536) ThrowFileError(name, "variable LF has an implausible size " + text);
  if (dims[4] != 1 && dims[4] != 3 && dims[4] != 4)
    ThrowFileError(name, "variable LF has " + std::to_string(dims[4]) +
                             " channels; expected 3 (RGB), 4 (RGB and weight, LFToolbox) or 1");
  LightFieldShape shape;
  shape.nv = static_cast<int>(dims[0]);
  shape.nu = static_cast<int>(dims[1]);
  shape.height = static_cast<int>(dims[2]);
  shape.width = static_cast<int>(dims[3]);
  shape.channels = dims[4] == 1 ? 1 : 3;
  return shape;
}

// Copies column-major samples LF(v, u, y, x, c) into the light field (and its weights when there is a 4th channel),
// scaled by `scale`.
template <typename T>
void FromMatlabOrder(const T* data, int channels_in_file, double scale, LightField& light_field) {
  const LightFieldShape& shape = light_field.shape();
  const std::size_t nv = static_cast<std::size_t>(shape.nv), nu = static_cast<std::size_t>(shape.nu);
  const std::size_t h = static_cast<std::size_t>(shape.height), w = static_cast<std::size_t>(shape.width);
  const std::size_t plane = nv * nu * h * w;  // one channel
  const int colour = std::min(channels_in_file, 3);
  if (channels_in_file == 4) light_field.EnableWeights();
  const int rows = shape.nv * shape.nu * shape.height;
#pragma omp parallel for schedule(static)
  for (int row = 0; row < rows; ++row) {
    const std::size_t y = static_cast<std::size_t>(row) % h;
    const std::size_t camera = static_cast<std::size_t>(row) / h;
    const ViewIndex view = ViewFromCameraNumber(static_cast<int>(camera), shape.nu);
    const std::size_t v = static_cast<std::size_t>(view.v), u = static_cast<std::size_t>(view.u);
    float* out = light_field.ViewData(view) + y * w * static_cast<std::size_t>(shape.channels);
    float* weight = channels_in_file == 4 ? light_field.weights().ViewData(view) + y * w : nullptr;
    for (std::size_t x = 0; x < w; ++x) {
      const std::size_t base = v + nv * (u + nu * (y + h * x));
      for (int c = 0; c < shape.channels; ++c)
        out[x * static_cast<std::size_t>(shape.channels) + static_cast<std::size_t>(c)] =
            static_cast<float>(data[base + plane * static_cast<std::size_t>(std::min(c, colour - 1))] * scale);
      if (weight) weight[x] = static_cast<float>(data[base + plane * 3] * scale);
    }
  }
}

LightField ReadV73(const fs::path& path) {
  const std::string name = path.string();
  H5::Exception::dontPrint();
  try {
    const ForeignCrashGuard guard(name, "libhdf5");
    const H5::H5File file(name, H5F_ACC_RDONLY);
    if (!file.nameExists(kVariable)) ThrowFileError(name, "MATLAB v7.3 file without a variable 'LF'");
    const H5::DataSet dataset = file.openDataSet(kVariable);
    CheckDeclaredStorage(dataset);
    const H5::DataSpace space = dataset.getSpace();
    const int rank = space.getSimpleExtentNdims();
    std::vector<hsize_t> reversed(static_cast<std::size_t>(std::max(rank, 0)));
    space.getSimpleExtentDims(reversed.data());
    const std::vector<std::uint64_t> dims(reversed.rbegin(), reversed.rend());  // MATLAB order
    const LightFieldShape shape = ShapeFromMatlabDims(dims, name);
    CheckDeclaredAllocation(name + ": variable LF", SaturatingBytes(dims, 2 * sizeof(float)), FileBytes(path));
    double scale = 1.0;
    if (dataset.getTypeClass() == H5T_INTEGER) {
      const H5::IntType type = dataset.getIntType();
      if (type.getSign() != H5T_SGN_NONE || (type.getSize() != 1 && type.getSize() != 2))
        ThrowFileError(name, "variable LF holds integers other than uint8/uint16");
      scale = type.getSize() == 1 ? 1.0 / 255.0 : 1.0 / 65535.0;
    } else if (dataset.getTypeClass() != H5T_FLOAT) {
      ThrowFileError(name, "variable LF holds neither numbers of a known type");
    }
    std::vector<float> samples(SaturatingBytes(dims, 1));
    dataset.read(samples.data(), H5::PredType::NATIVE_FLOAT);
    LightField light_field(shape);
    FromMatlabOrder(samples.data(), static_cast<int>(dims[4]), scale, light_field);
    return light_field;
  } catch (const H5::Exception& error) {
    ThrowFileError(name, "HDF5 read failed in " + error.getFuncName() + ": " + error.getDetailMsg());
  }
}

struct MatCloser {
  void operator()(mat_t* mat) const { Mat_Close(mat); }
};
struct VarFreer {
  void operator()(matvar_t* var) const { Mat_VarFree(var); }
};

// matio reports problems on stderr by itself, which would break the one-line error contract; lfsp reports them.
void SilenceMatio() {
  static const bool silenced = [] {
    Mat_LogInitFunc("lfsp", [](int, char*) {});
    return true;
  }();
  (void)silenced;
}

LightField ReadV5(const fs::path& path) {
  const std::string name = path.string();
  CheckMat5Structure(path);
  SilenceMatio();
  const ForeignCrashGuard guard(name, "libmatio");
  std::unique_ptr<mat_t, MatCloser> mat(Mat_Open(name.c_str(), MAT_ACC_RDONLY));
  if (!mat) ThrowFileError(name, "not a MATLAB .mat file (or an unreadable one)");
  std::unique_ptr<matvar_t, VarFreer> info(Mat_VarReadInfo(mat.get(), kVariable));
  if (!info) ThrowFileError(name, "no variable 'LF' (a light field LF(v, u, y, x, c))");
  if (info->rank < 0 || info->dims == nullptr) ThrowFileError(name, "variable LF has no dimensions");
  const std::vector<std::uint64_t> dims(info->dims, info->dims + info->rank);
  const LightFieldShape shape = ShapeFromMatlabDims(dims, name);
  double scale = 1.0;
  std::size_t element = 0;
  switch (info->class_type) {
    case MAT_C_UINT8:
      scale = 1.0 / 255.0;
      element = 1;
      break;
    case MAT_C_UINT16:
      scale = 1.0 / 65535.0;
      element = 2;
      break;
    case MAT_C_SINGLE:
      element = 4;
      break;
    case MAT_C_DOUBLE:
      element = 8;
      break;
    default:
      ThrowFileError(name, "variable LF is not uint8, uint16, single or double");
  }
  if (info->isComplex) ThrowFileError(name, "variable LF is complex");
  CheckDeclaredAllocation(name + ": variable LF", SaturatingBytes(dims, element + sizeof(float)), FileBytes(path));
  // Read again with the data (matio reads a variable's data with its header).
  const matio_classes declared_class = info->class_type;
  info.reset();
  Mat_Rewind(mat.get());
  std::unique_ptr<matvar_t, VarFreer> var(Mat_VarRead(mat.get(), kVariable));
  if (!var || var->data == nullptr) ThrowFileError(name, "variable LF cannot be read (truncated or corrupt?)");
  if (var->class_type != declared_class || var->rank != 5 || !std::equal(dims.begin(), dims.end(), var->dims))
    ThrowFileError(name, "variable LF changed size between its header and its data");
  LightField light_field(shape);
  const int channels = static_cast<int>(dims[4]);
  switch (var->class_type) {
    case MAT_C_UINT8:
      FromMatlabOrder(static_cast<const std::uint8_t*>(var->data), channels, scale, light_field);
      break;
    case MAT_C_UINT16:
      FromMatlabOrder(static_cast<const std::uint16_t*>(var->data), channels, scale, light_field);
      break;
    case MAT_C_SINGLE:
      FromMatlabOrder(static_cast<const float*>(var->data), channels, scale, light_field);
      break;
    default:
      FromMatlabOrder(static_cast<const double*>(var->data), channels, scale, light_field);
      break;
  }
  return light_field;
}

}  // namespace

LightField ReadMatLightField(const fs::path& path) {
  const std::string name = path.string();
  RequireRegularFile(path);
  H5::Exception::dontPrint();
  LightField light_field = H5Fis_hdf5(name.c_str()) > 0 ? ReadV73(path) : ReadV5(path);
  light_field.transfer = Transfer::kSrgb;  // the file does not say; assumed display-encoded, as PNG views are
  light_field.metadata = Metadata::object();
  return light_field;
}

void WriteMatLightField(const LightField& light_field, const fs::path& path) {
  const std::string name = path.string();
  if (light_field.empty()) ThrowFileError(name, "refusing to write an empty light field");
  const LightFieldShape& shape = light_field.shape();
  const std::size_t nv = static_cast<std::size_t>(shape.nv), nu = static_cast<std::size_t>(shape.nu);
  const std::size_t h = static_cast<std::size_t>(shape.height), w = static_cast<std::size_t>(shape.width);
  const std::size_t plane = nv * nu * h * w;
  std::vector<std::uint16_t> data(plane * 4);
  const auto quantise = [](float value) { return static_cast<std::uint16_t>(SampleLevel(value, 65535.0f)); };
  const int rows = shape.nv * shape.nu * shape.height;
#pragma omp parallel for schedule(static)
  for (int row = 0; row < rows; ++row) {
    const std::size_t y = static_cast<std::size_t>(row) % h;
    const ViewIndex view = ViewFromCameraNumber(row / shape.height, shape.nu);
    const std::size_t v = static_cast<std::size_t>(view.v), u = static_cast<std::size_t>(view.u);
    const float* in = light_field.ViewData(view) + y * w * static_cast<std::size_t>(shape.channels);
    const float* weight = light_field.HasWeights() ? light_field.weights().ViewData(view) + y * w : nullptr;
    for (std::size_t x = 0; x < w; ++x) {
      const std::size_t base = v + nv * (u + nu * (y + h * x));
      for (std::size_t c = 0; c < 3; ++c)
        data[base + plane * c] =
            quantise(in[x * static_cast<std::size_t>(shape.channels) + std::min<std::size_t>(c, shape.channels - 1)]);
      data[base + plane * 3] = weight ? quantise(weight[x]) : 65535;
    }
  }
  const bool large = data.size() * sizeof(std::uint16_t) >= (2ull << 30);
  SilenceMatio();
  AtomicOutput output(path);
  {
    std::unique_ptr<mat_t, MatCloser> mat(
        Mat_CreateVer(output.temporary().c_str(), nullptr, large ? MAT_FT_MAT73 : MAT_FT_MAT5));
    if (!mat) ThrowFileError(name, "cannot create the .mat file");
    std::size_t dims[5] = {nv, nu, h, w, 4};
    std::unique_ptr<matvar_t, VarFreer> var(
        Mat_VarCreate(kVariable, MAT_C_UINT16, MAT_T_UINT16, 5, dims, data.data(), MAT_F_DONT_COPY_DATA));
    if (!var || Mat_VarWrite(mat.get(), var.get(), MAT_COMPRESSION_ZLIB) != 0)
      ThrowFileError(name, "writing variable LF failed");
  }
  output.Commit();
}

}  // namespace lfsp
