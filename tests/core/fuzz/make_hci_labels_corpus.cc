// Writes the committed seeds of the hci_labels fuzz target (tests/core/fuzz/corpus/hci_labels): old-HCI labels.h5
// files whose GT_LABELS match or miss the target's lf.h5 (3 x 3 views of 8 x 6 pixels). Not part of the build; to
// regenerate (deterministic: no time stamps):
//   g++ -std=c++20 -I/usr/include/hdf5/serial tests/core/fuzz/make_hci_labels_corpus.cc \
//       -L/usr/lib/x86_64-linux-gnu/hdf5/serial -lhdf5 -o /tmp/make_hci_labels_corpus
//   /tmp/make_hci_labels_corpus tests/core/fuzz/corpus/hci_labels

#include <hdf5.h>

#include <cstdio>
#include <string>
#include <vector>

namespace {

// One file holding `dataset` of `type` and shape `dims` (chunked per view and gzipped when `gzip`), values i % 4
// (minus one every seventh value when `negative`).
void Write(const std::string& path, const char* dataset, hid_t type, std::vector<hsize_t> dims, bool gzip = false,
           bool negative = false) {
  hsize_t count = 1;
  for (const hsize_t d : dims) count *= d;
  std::vector<double> values(count);
  for (hsize_t i = 0; i < count; ++i) values[i] = negative && i % 7 == 0 ? -1.0 : static_cast<double>(i % 4);
  const hid_t create = H5Pcreate(H5P_FILE_CREATE);
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, create, H5P_DEFAULT);
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t properties = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_obj_track_times(properties, false);
  if (gzip) {
    std::vector<hsize_t> chunk = dims;
    chunk[0] = chunk[1] = 1;
    H5Pset_chunk(properties, static_cast<int>(chunk.size()), chunk.data());
    H5Pset_shuffle(properties);
    H5Pset_deflate(properties, 6);
  }
  const hid_t set = H5Dcreate2(file, dataset, type, space, H5P_DEFAULT, properties, H5P_DEFAULT);
  H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Dclose(set);
  H5Pclose(properties);
  H5Sclose(space);
  H5Fclose(file);
  H5Pclose(create);
  std::printf("%s\n", path.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s FOLDER\n", argv[0]);
    return 2;
  }
  const std::string folder = argv[1];
  Write(folder + "/uint8_views.h5", "GT_LABELS", H5T_STD_U8LE, {3, 3, 6, 8});
  Write(folder + "/uint16_gzip_views.h5", "GT_LABELS", H5T_STD_U16LE, {3, 3, 6, 8}, true);
  Write(folder + "/int32_centre_view.h5", "GT_LABELS", H5T_STD_I32LE, {6, 8});
  Write(folder + "/int8_negative.h5", "GT_LABELS", H5T_STD_I8LE, {3, 3, 6, 8}, false, true);
  Write(folder + "/wrong_view_count.h5", "GT_LABELS", H5T_STD_U8LE, {3, 2, 6, 8});
  Write(folder + "/wrong_view_size.h5", "GT_LABELS", H5T_STD_U8LE, {3, 3, 8, 6});
  Write(folder + "/three_dimensions.h5", "GT_LABELS", H5T_STD_U8LE, {3, 6, 8});
  Write(folder + "/float_labels.h5", "GT_LABELS", H5T_IEEE_F32LE, {3, 3, 6, 8});
  Write(folder + "/other_dataset.h5", "GT_DEPTH", H5T_IEEE_F32LE, {6, 8});
  // Not HDF5 at all: a labels.h5 that is a text file.
  if (std::FILE* text = std::fopen((folder + "/not_hdf5.h5").c_str(), "wb")) {
    std::fputs("GT_LABELS\n", text);
    std::fclose(text);
  }
  return 0;
}
