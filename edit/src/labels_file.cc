#include "lfsp/edit/labels_file.h"

#include <H5Cpp.h>

#include <string>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/input_limits.h"

namespace lfsp::edit {
namespace fs = std::filesystem;

Labels ReadLabelsFile(const fs::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) ThrowFileError(name, "no such file");
  H5::Exception::dontPrint();
  if (H5Fis_hdf5(name.c_str()) <= 0) ThrowFileError(name, "not an HDF5 file");
  try {
    const H5::H5File file(name, H5F_ACC_RDONLY);
    std::string dataset_name;
    for (const char* candidate : {"labels", "GT_LABELS"})
      if (file.nameExists(candidate)) {
        dataset_name = candidate;
        break;
      }
    if (dataset_name.empty()) ThrowFileError(name, "has neither a 'labels' nor a 'GT_LABELS' dataset");
    const H5::DataSet dataset = file.openDataSet(dataset_name);
    if (dataset.getTypeClass() != H5T_INTEGER)
      ThrowFileError(name, "dataset " + dataset_name + " does not hold integers");
    const H5::DataSpace space = dataset.getSpace();
    if (space.getSimpleExtentNdims() != 4)
      ThrowFileError(name, "dataset " + dataset_name + " has rank " + std::to_string(space.getSimpleExtentNdims()) +
                               ", expected nv x nu x H x W");
    hsize_t dims[4] = {0, 0, 0, 0};
    space.getSimpleExtentDims(dims);
    for (const hsize_t dim : dims)
      if (dim == 0 || dim > 65536) ThrowFileError(name, "dataset " + dataset_name + " has an implausible shape");
    if (static_cast<double>(dims[0]) * static_cast<double>(dims[1]) * static_cast<double>(dims[2]) *
            static_cast<double>(dims[3]) >
        4.0e9)
      ThrowFileError(name, "dataset " + dataset_name + " is too large (more than 4e9 rays)");
    CheckDeclaredAllocation(name + ": dataset " + dataset_name,
                            SaturatingBytes({dims[0], dims[1], dims[2], dims[3]}, sizeof(std::int32_t)),
                            FileBytes(path));
    LightFieldShape shape;
    shape.nv = static_cast<int>(dims[0]);
    shape.nu = static_cast<int>(dims[1]);
    shape.height = static_cast<int>(dims[2]);
    shape.width = static_cast<int>(dims[3]);
    shape.channels = 1;
    Labels labels(shape);
    dataset.read(labels.data(), H5::PredType::NATIVE_INT32);  // HDF5 converts any integer type
    RequireValidLabelValues(labels, name + ": dataset " + dataset_name);
    return labels;
  } catch (const H5::Exception& error) {
    ThrowFileError(name, "HDF5 read failed in " + error.getFuncName() + ": " + error.getDetailMsg());
  }
}

void CheckLabelsMatch(const Labels& labels, const LightFieldShape& shape, const std::string& what) {
  const LightFieldShape& have = labels.shape();
  if (have.nu != shape.nu || have.nv != shape.nv || have.width != shape.width || have.height != shape.height)
    throw Error(what + ": labels are " + std::to_string(have.nv) + "x" + std::to_string(have.nu) + " views of " +
                std::to_string(have.width) + "x" + std::to_string(have.height) + " but the light field is " +
                ToString(shape));
}

}  // namespace lfsp::edit
