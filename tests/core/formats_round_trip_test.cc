// Round trips between every light-field format must be exact for 8- and 16-bit data (issue 2).

#include <gtest/gtest.h>
#include <hdf5.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <thread>

#include "lfsp/core/error.h"
#include "lfsp/core/eslf.h"
#include "lfsp/core/hci_config.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/views_folder.h"
#include "test_support.h"

namespace lfsp {
namespace {

using lfsp::testing::TempDir;

// A 5x5 light field of 64x48 views whose samples are exact k / (2^bits - 1) values.
LightField QuantisedLightField(int bits, unsigned seed) {
  LightField light_field({5, 5, 64, 48, 3});
  std::mt19937 random(seed);
  const int levels = (1 << bits) - 1;
  std::uniform_int_distribution<int> level(0, levels);
  for (std::size_t i = 0; i < light_field.size(); ++i)
    light_field.data()[i] = static_cast<float>(level(random)) / static_cast<float>(levels);
  light_field.metadata["meta"]["scene"] = "round-trip";
  SetDisparityRange(light_field.metadata, {-1.5f, 2.25f});
  return light_field;
}

void ExpectSameSamples(const LightField& a, const LightField& b) {
  ASSERT_EQ(a.shape(), b.shape());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differing += a.data()[i] != b.data()[i];
  EXPECT_EQ(differing, 0u) << "samples differ after the round trip";
}

class FormatsRoundTrip : public ::testing::TestWithParam<int> {};

TEST_P(FormatsRoundTrip, ViewsFolderToHdf5ToEslfAndBackIsExact) {
  const int bits = GetParam();
  TempDir temp;
  const LightField original = QuantisedLightField(bits, 7u + static_cast<unsigned>(bits));

  ViewsFolderOptions views_options;
  views_options.bit_depth = bits;
  WriteViewsFolder(original, temp / "views", views_options);
  const LightField from_views = ReadViewsFolder(temp / "views");
  ExpectSameSamples(original, from_views);
  EXPECT_EQ(from_views.metadata["meta"]["scene"], "round-trip");
  ASSERT_TRUE(DisparityRangeFromMetadata(from_views.metadata).has_value());
  EXPECT_FLOAT_EQ(DisparityRangeFromMetadata(from_views.metadata)->max, 2.25f);

  Bundle bundle;
  bundle.light_field = from_views;
  WriteBundle(bundle, temp / "lf.h5");
  const Bundle from_h5 = ReadBundle(temp / "lf.h5");
  ExpectSameSamples(original, from_h5.light_field);
  EXPECT_EQ(from_h5.light_field.metadata, from_views.metadata);

  EslfOptions eslf_options;
  eslf_options.bit_depth = bits;
  WriteEslf(from_h5.light_field, temp / "lf.eslf.png", eslf_options);
  const LightField from_eslf = ReadEslf(temp / "lf.eslf.png");
  ExpectSameSamples(original, from_eslf);

  WriteViewsFolder(from_eslf, temp / "views_again", views_options);
  ExpectSameSamples(original, ReadViewsFolder(temp / "views_again"));
}

TEST_P(FormatsRoundTrip, QuantisedHdf5StorageIsExactForItsBitDepth) {
  const int bits = GetParam();
  TempDir temp;
  Bundle bundle;
  bundle.light_field = QuantisedLightField(bits, 3);
  BundleWriteOptions options;
  options.storage = bits == 8 ? SampleStorage::kUint8 : SampleStorage::kUint16;
  // Compressed, the samples are quantised view by view as they are compressed; uncompressed, all at once: the same.
  for (const int level : {4, 0}) {
    SCOPED_TRACE(level);
    options.compression_level = level;
    WriteBundle(bundle, temp / "q.h5", options);
    ExpectSameSamples(bundle.light_field, ReadBundle(temp / "q.h5").light_field);
  }
}

INSTANTIATE_TEST_SUITE_P(BitDepths, FormatsRoundTrip, ::testing::Values(8, 16));

TEST(EslfLayout, MacroPixelHoldsAllAngularSamples) {
  TempDir temp;
  LightField light_field({3, 2, 4, 5, 3});
  for (int v = 0; v < 2; ++v)
    for (int u = 0; u < 3; ++u) light_field.at({u, v}, 4, 1, 0) = static_cast<float>(10 * v + u) / 255.0f;
  WriteEslf(light_field, temp / "e.png");
  const ImageFile image = ReadImage(temp / "e.png");
  ASSERT_EQ(image.pixels.cols, 4 * 3);
  ASSERT_EQ(image.pixels.rows, 5 * 2);
  // image(y*nv + v, x*nu + u) = view(u, v)(y, x)
  EXPECT_FLOAT_EQ(image.pixels.at<cv::Vec3f>(4 * 2 + 1, 1 * 3 + 2)[0], 12.0f / 255.0f);
  EXPECT_FLOAT_EQ(image.pixels.at<cv::Vec3f>(4 * 2 + 0, 1 * 3 + 0)[0], 0.0f);
}

TEST(EslfLayout, ForeignEslfNeedsTheAngularSize) {
  TempDir temp;
  cv::Mat plain(28, 42, CV_32FC3, cv::Scalar(0.5, 0.25, 1.0));
  WriteImage(plain, temp / "foreign.png");
  EXPECT_THROW(ReadEslf(temp / "foreign.png"), Error);
  EslfOptions options;
  options.nu = 14;
  options.nv = 14;
  const LightField light_field = ReadEslf(temp / "foreign.png", options);
  EXPECT_EQ(light_field.shape(), (LightFieldShape{14, 14, 3, 2, 3}));
}

TEST(Hdf5Bundle, DisparityLabelsWeightsAndTransferSurvive) {
  TempDir temp;
  Bundle bundle;
  bundle.light_field = QuantisedLightField(8, 11);
  bundle.light_field.transfer = Transfer::kLinear;
  bundle.light_field.EnableWeights(0.0f);
  for (std::size_t i = 0; i < bundle.light_field.weights().size(); ++i)
    bundle.light_field.weights().data()[i] = static_cast<float>(i % 97) / 96.0f;
  DisparityMap disparity(64, 48);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) disparity.at(y, x) = 0.01f * static_cast<float>(x) - 0.02f * static_cast<float>(y);
  bundle.disparity = disparity;
  Labels labels(bundle.light_field.shape());
  for (std::size_t i = 0; i < labels.size(); ++i) labels.data()[i] = static_cast<int>(i % 1000) - 1;
  bundle.labels = labels;
  WriteBundle(bundle, temp / "full.h5");

  const Bundle read = ReadBundle(temp / "full.h5");
  EXPECT_EQ(read.light_field.transfer, Transfer::kLinear);
  ASSERT_TRUE(read.light_field.HasWeights());
  EXPECT_EQ(read.light_field.weights().at({4, 3}, 47, 63), bundle.light_field.weights().at({4, 3}, 47, 63));
  ASSERT_TRUE(read.disparity.has_value());
  EXPECT_EQ(read.disparity->at(47, 63), disparity.at(47, 63));
  EXPECT_EQ(read.disparity->at(3, 5), disparity.at(3, 5));
  ASSERT_TRUE(read.labels.has_value());
  EXPECT_TRUE(std::equal(labels.data(), labels.data() + labels.size(), read.labels->data()));
}

// The commands' compact bundles: view chunks deflated in parallel and written whole, 16-bit samples and weights for a
// sensor decode, labels narrowed to the smallest type that holds them. HDF5 must read back what was meant.
TEST(Hdf5Bundle, CompactBundlesReadBackWhatWasWritten) {
  TempDir dir;
  Bundle bundle;
  bundle.light_field = LightField(LightFieldShape{3, 3, 5, 7, 3});
  bundle.light_field.metadata["decode"] = {{"source", "capture.LFR"}};  // a sensor decode: 16-bit storage
  bundle.light_field.EnableWeights();
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (std::size_t i = 0; i < bundle.light_field.size(); ++i) bundle.light_field.data()[i] = unit(random);
  for (std::size_t i = 0; i < bundle.light_field.weights().size(); ++i)
    bundle.light_field.weights().data()[i] = unit(random);
  const BundleWriteOptions compact = CompactBundleOptions(bundle.light_field);
  EXPECT_EQ(compact.storage, SampleStorage::kUint16);
  EXPECT_GT(compact.compression_level, 0);
  // Labels in each of the three stored types: uint16, int16 (unlabelled rays are -1), int32.
  for (const std::int32_t offset : {0, -1, 100000}) {
    Labels labels(bundle.light_field.shape());
    for (std::size_t i = 0; i < labels.size(); ++i)
      labels.data()[i] = (i % 5 == 0 && offset < 0) ? -1 : static_cast<std::int32_t>(i % 300) + std::max(offset, 0);
    bundle.labels = labels;
    const std::filesystem::path path = dir / ("compact" + std::to_string(offset) + ".h5");
    WriteBundle(bundle, path, compact);
    const Bundle read = ReadBundle(path);
    ASSERT_EQ(read.light_field.shape(), bundle.light_field.shape());
    for (std::size_t i = 0; i < bundle.light_field.size(); ++i)
      ASSERT_NEAR(read.light_field.data()[i], bundle.light_field.data()[i], 0.5f / 65535.0f + 1e-7f) << i;
    ASSERT_TRUE(read.light_field.HasWeights());
    for (std::size_t i = 0; i < bundle.light_field.weights().size(); ++i)
      ASSERT_NEAR(read.light_field.weights().data()[i], bundle.light_field.weights().data()[i],
                  0.5f / 65535.0f + 1e-7f);
    ASSERT_TRUE(read.labels.has_value());
    for (std::size_t i = 0; i < labels.size(); ++i) ASSERT_EQ(read.labels->data()[i], labels.data()[i]) << offset;
  }
  // Without the decoder's record the samples stay float32, exactly.
  bundle.light_field.metadata.erase("decode");
  const std::filesystem::path exact = dir / "exact.h5";
  WriteBundle(bundle, exact, CompactBundleOptions(bundle.light_field));
  const Bundle read = ReadBundle(exact);
  for (std::size_t i = 0; i < bundle.light_field.size(); ++i)
    ASSERT_EQ(read.light_field.data()[i], bundle.light_field.data()[i]);
}

// Views read from 8- or 16-bit images hold exact levels; CompactBundleOptions stores them as 8- or 16-bit integers,
// and they must read back bit for bit. Anything that is not a level (an ulp off, NaN, -0, beyond 1) stays float32.
TEST(Hdf5Bundle, CompactBundlesStoreExactLevelsAsIntegersAndReadThemBack) {
  TempDir dir;
  const auto bits_equal = [](const float* a, const float* b, std::size_t count) {
    return std::memcmp(a, b, count * sizeof(float)) == 0;
  };
  const auto write_and_read = [&](const Bundle& bundle, const char* name) {
    WriteBundle(bundle, dir / name, CompactBundleOptions(bundle.light_field));
    return ReadBundle(dir / name);
  };
  Bundle bundle;
  bundle.light_field = LightField(LightFieldShape{3, 3, 9, 11, 3});
  const std::size_t count = bundle.light_field.size();
  float* samples = bundle.light_field.data();
  for (std::size_t i = 0; i < count; ++i) samples[i] = static_cast<float>((i * 37) % 256) / 255.0f;
  EXPECT_EQ(CompactBundleOptions(bundle.light_field).storage, SampleStorage::kUint8);
  Bundle read = write_and_read(bundle, "eight.h5");
  EXPECT_TRUE(bits_equal(read.light_field.data(), samples, count));

  for (std::size_t i = 0; i < count; ++i) samples[i] = static_cast<float>((i * 7919) % 65536) / 65535.0f;
  EXPECT_EQ(CompactBundleOptions(bundle.light_field).storage, SampleStorage::kUint16);
  read = write_and_read(bundle, "sixteen.h5");
  EXPECT_TRUE(bits_equal(read.light_field.data(), samples, count));
  // 16-bit samples take 16-bit weights beside them: exact weights keep the 16-bit storage, others make it float32.
  bundle.light_field.EnableWeights();
  float* weights = bundle.light_field.weights().data();
  const std::size_t weight_count = bundle.light_field.weights().size();
  for (std::size_t i = 0; i < weight_count; ++i) weights[i] = static_cast<float>(i % 65536) / 65535.0f;
  EXPECT_EQ(CompactBundleOptions(bundle.light_field).storage, SampleStorage::kUint16);
  read = write_and_read(bundle, "sixteen_weighted.h5");
  EXPECT_TRUE(bits_equal(read.light_field.weights().data(), weights, weight_count));
  weights[5] = 0.3f;
  EXPECT_EQ(CompactBundleOptions(bundle.light_field).storage, SampleStorage::kFloat32);
  read = write_and_read(bundle, "sixteen_inexact_weight.h5");
  EXPECT_TRUE(bits_equal(read.light_field.weights().data(), weights, weight_count));
  EXPECT_TRUE(bits_equal(read.light_field.data(), samples, count));

  bundle.light_field = LightField(LightFieldShape{3, 3, 9, 11, 3});
  samples = bundle.light_field.data();
  for (const float odd :
       {std::nextafter(128.0f / 255.0f, 1.0f), std::numeric_limits<float>::quiet_NaN(), -0.0f, 1.5f, -0.25f}) {
    for (std::size_t i = 0; i < count; ++i) samples[i] = static_cast<float>(i % 256) / 255.0f;
    samples[count / 2] = odd;
    EXPECT_EQ(CompactBundleOptions(bundle.light_field).storage, SampleStorage::kFloat32) << odd;
  }
  samples[count / 2] = std::nextafter(128.0f / 255.0f, 1.0f);
  read = write_and_read(bundle, "float.h5");
  EXPECT_TRUE(bits_equal(read.light_field.data(), samples, count));
}

// Compressed bundles are inflated view by view in parallel (ReadViewChunks); a damaged chunk must still end in a
// one-line error that names the file, never in garbage samples or a crash.
TEST(Hdf5Bundle, ADamagedViewChunkIsAnErrorNamingTheFile) {
  TempDir temp;
  Bundle bundle;
  bundle.light_field = QuantisedLightField(16, 3);
  BundleWriteOptions options;
  options.compression_level = 1;
  const std::filesystem::path path = temp / "damaged.h5";
  WriteBundle(bundle, path, options);
  ExpectSameSamples(ReadBundle(path).light_field, bundle.light_field);  // the parallel path reads it back exactly
  std::string bytes = lfsp::testing::ReadBytes(path);
  // The 25 compressed views fill most of the file; overwrite a run in the middle of them.
  for (std::size_t i = bytes.size() / 2; i < bytes.size() / 2 + 64; ++i) bytes[i] = static_cast<char>(i * 37);
  lfsp::testing::WriteBytes(path, bytes);
  try {
    (void)ReadBundle(path);
    FAIL() << "a damaged chunk was read without an error";
  } catch (const Error& error) {
    std::printf("damaged chunk: %s\n", error.what());
    EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
    // Only the parallel reader says this (HDF5's own read fails otherwise): the chunks took that path.
    EXPECT_NE(std::string(error.what()).find("does not inflate"), std::string::npos) << error.what();
  }
}

// The samples of dataset LF as HDF5's own deflate filter (zlib) inflates them, past lfsp's parallel reader.
std::vector<std::uint16_t> LfThroughHdf5(const std::filesystem::path& path, std::size_t count) {
  std::vector<std::uint16_t> values(count);
  const hid_t file = H5Fopen(path.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t dataset = H5Dopen2(file, "LF", H5P_DEFAULT);
  const herr_t status = H5Dread(dataset, H5T_NATIVE_UINT16, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Dclose(dataset);
  H5Fclose(file);
  EXPECT_GE(status, 0) << path;
  return values;
}

// The first bytes of view (0, 0)'s stored chunk of dataset LF.
std::vector<std::uint8_t> FirstChunkStart(const std::filesystem::path& path, std::size_t bytes) {
  const hid_t file = H5Fopen(path.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t dataset = H5Dopen2(file, "LF", H5P_DEFAULT);
  const hsize_t offset[5] = {0, 0, 0, 0, 0};
  hsize_t stored = 0;
  H5Dget_chunk_storage_size(dataset, offset, &stored);
  std::vector<std::uint8_t> chunk(static_cast<std::size_t>(stored));
  std::uint32_t filters = 0;
  H5Dread_chunk(dataset, H5P_DEFAULT, offset, &filters, chunk.data());
  H5Dclose(dataset);
  H5Fclose(file);
  chunk.resize(std::min(bytes, chunk.size()));
  return chunk;
}

// A byte plane of noise (a decode's low sample bytes) is stored in the chunk's zlib stream, not deflated, and the
// rest deflated after it: both HDF5's zlib and lfsp's reader must inflate that to the samples, for 16-bit samples
// (the low plane stored, the high one deflated) and 8-bit ones (the only plane stored, then an empty final block).
TEST(Hdf5Bundle, NoisePlanesStoredUndeflatedReadBackThroughHdf5AndLfsp) {
  TempDir temp;
  for (const int bits : {16, 8}) {
    Bundle bundle;
    bundle.light_field = LightField({5, 5, 64, 48, 3});
    std::mt19937 random(11);
    const int levels = (1 << bits) - 1;
    // 16-bit: a smooth high byte over a noise low byte; 8-bit: noise.
    std::uniform_int_distribution<int> noise(0, 255);
    for (std::size_t i = 0; i < bundle.light_field.size(); ++i) {
      const int level = bits == 16 ? static_cast<int>((i / 3000) % 256) * 256 + noise(random) : noise(random);
      bundle.light_field.data()[i] = static_cast<float>(level) / static_cast<float>(levels);
    }
    BundleWriteOptions options;
    options.storage = bits == 16 ? SampleStorage::kUint16 : SampleStorage::kUint8;
    options.compression_level = 1;
    const std::filesystem::path path = temp / ("noise" + std::to_string(bits) + ".h5");
    WriteBundle(bundle, path, options);
    ExpectSameSamples(ReadBundle(path).light_field, bundle.light_field);
    const std::vector<std::uint16_t> through_hdf5 = LfThroughHdf5(path, bundle.light_field.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < through_hdf5.size(); ++i)
      differing += through_hdf5[i] != static_cast<std::uint16_t>(std::lround(bundle.light_field.data()[i] * levels));
    EXPECT_EQ(differing, 0u) << bits << "-bit samples as HDF5's zlib inflates them";
    // zlib header, then a stored block that is not final (header byte 0) holding the whole plane: 64 x 48 x 3 =
    // 9216 = 0x2400 bytes (LEN, then NLEN, little-endian).
    const std::vector<std::uint8_t> start = FirstChunkStart(path, 7);
    EXPECT_EQ(start, (std::vector<std::uint8_t>{0x78, 0x01, 0x00, 0x00, 0x24, 0xFF, 0xDB})) << bits;
  }
}

// Uncompressed bundles (the simulator's ground truth) are contiguous datasets, read straight from the file in 16 MB
// pieces on all cores (ReadContiguous): every sample and weight must come back, past the pieces' seams, as float32
// and as 16-bit storage.
TEST(Hdf5Bundle, ContiguousDatasetsReadBackExactlyAcrossPieces) {
  TempDir temp;
  Bundle bundle;
  bundle.light_field = LightField({5, 5, 300, 200, 3});  // 18 MB of float32 samples: two pieces
  bundle.light_field.EnableWeights();
  std::mt19937 random(3);
  std::uniform_int_distribution<int> level(0, 65535);
  for (std::size_t i = 0; i < bundle.light_field.size(); ++i)
    bundle.light_field.data()[i] = static_cast<float>(level(random)) / 65535.0f;
  for (std::size_t i = 0; i < bundle.light_field.weights().size(); ++i)
    bundle.light_field.weights().data()[i] = static_cast<float>(level(random)) / 65535.0f;
  for (const SampleStorage storage : {SampleStorage::kFloat32, SampleStorage::kUint16}) {
    const std::filesystem::path path = temp / (storage == SampleStorage::kFloat32 ? "float.h5" : "uint16.h5");
    WriteBundle(bundle, path, {storage, 0});
    const Bundle read = ReadBundle(path);
    ExpectSameSamples(read.light_field, bundle.light_field);
    ASSERT_TRUE(read.light_field.HasWeights());
    EXPECT_EQ(std::memcmp(read.light_field.weights().data(), bundle.light_field.weights().data(),
                          bundle.light_field.weights().size() * sizeof(float)),
              0);
  }
}

// 16-bit labels are read as stored and widened in place in rounds (hdf5_bundle.cc): an odd count large enough for
// several rounds, both signs, contiguous and in deflated view chunks, must read back every label exactly.
TEST(Hdf5Bundle, SixteenBitLabelsWidenedInPlaceReadBackExactly) {
  TempDir temp;
  Bundle bundle;
  bundle.light_field = LightField({5, 5, 47, 61, 3});  // 71,675 labels
  for (const bool negative : {false, true}) {
    Labels labels(bundle.light_field.shape());
    for (std::size_t i = 0; i < labels.size(); ++i)
      labels.data()[i] = negative ? (i % 7 == 0 ? -1 : static_cast<std::int32_t>(i % 30011))
                                  : static_cast<std::int32_t>((i * 7919) % 65536);
    bundle.labels = labels;
    for (const int level : {0, 1}) {
      const std::filesystem::path path =
          temp / ("labels_" + std::to_string(negative) + "_" + std::to_string(level) + ".h5");
      WriteBundle(bundle, path, {SampleStorage::kFloat32, level});
      const Bundle read = ReadBundle(path);
      ASSERT_TRUE(read.labels.has_value());
      EXPECT_EQ(std::memcmp(read.labels->data(), labels.data(), labels.size() * sizeof(std::int32_t)), 0)
          << "negative " << negative << ", level " << level;
      const Labels alone = ReadLabels(path);
      EXPECT_EQ(std::memcmp(alone.data(), labels.data(), labels.size() * sizeof(std::int32_t)), 0);
    }
  }
}

// The views of `block` of a light field or labels, copied out of the whole.
template <typename T>
void CopyBlock(const Array4D<T>& whole, const ViewBlock& block, Array4D<T>& part) {
  const std::size_t samples = whole.shape().ViewSamples();
  for (int v = 0; v < block.nv; ++v)
    for (int u = 0; u < block.nu; ++u) {
      const T* source = whole.ViewData(ViewIndex{block.first.u + u, block.first.v + v});
      std::copy(source, source + samples, part.ViewData(ViewIndex{u, v}));
    }
}

// Dataset LF chunked in half views (not one view per chunk, as WriteBundle never writes it): only HDF5 reads it.
void WriteHalfViewChunkedSamples(const LightField& light_field, const std::filesystem::path& path) {
  const LightFieldShape& shape = light_field.shape();
  const hsize_t dims[5] = {static_cast<hsize_t>(shape.nv), static_cast<hsize_t>(shape.nu),
                           static_cast<hsize_t>(shape.height), static_cast<hsize_t>(shape.width), 3};
  const hsize_t chunk[5] = {1, 1, static_cast<hsize_t>(shape.height / 2), static_cast<hsize_t>(shape.width), 3};
  const hid_t file = H5Fcreate(path.string().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t space = H5Screate_simple(5, dims, nullptr);
  const hid_t properties = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(properties, 5, chunk);
  const hid_t dataset = H5Dcreate2(file, "LF", H5T_IEEE_F32LE, space, H5P_DEFAULT, properties, H5P_DEFAULT);
  EXPECT_GE(H5Dwrite(dataset, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, light_field.data()), 0);
  H5Dclose(dataset);
  H5Pclose(properties);
  H5Sclose(space);
  H5Fclose(file);
}

// Parts of a bundle (issue 46: the pipeline reads the simulator's truth a row of views at a time) are exactly those
// views of the whole, whichever reader takes them: contiguous (float32, uint16), one deflated chunk per view, or
// HDF5's own; labels in each stored type; a block as wide as the light field (one run) or narrower (a run per row).
TEST(Hdf5Bundle, PartsOfABundleAreThoseViewsOfTheWhole) {
  TempDir temp;
  Bundle bundle;
  bundle.light_field = QuantisedLightField(16, 5);
  bundle.light_field.EnableWeights();
  for (std::size_t i = 0; i < bundle.light_field.weights().size(); ++i)
    bundle.light_field.weights().data()[i] = static_cast<float>(i % 65536) / 65535.0f;
  DisparityMap disparity(64, 48);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) disparity.at(y, x) = 0.01f * static_cast<float>(x * y);
  bundle.disparity = disparity;
  std::vector<std::filesystem::path> files;
  for (const std::int32_t offset : {0, -1, 100000}) {  // labels stored as uint16, int16, int32
    Labels labels(bundle.light_field.shape());
    for (std::size_t i = 0; i < labels.size(); ++i)
      labels.data()[i] = (i % 5 == 0 && offset < 0) ? -1 : static_cast<std::int32_t>(i % 3001) + std::max(offset, 0);
    bundle.labels = labels;
    for (const BundleWriteOptions options :
         {BundleWriteOptions{SampleStorage::kFloat32, 0}, BundleWriteOptions{SampleStorage::kUint16, 0},
          BundleWriteOptions{SampleStorage::kUint16, 1}}) {
      files.push_back(temp / ("parts_" + std::to_string(offset) + "_" + std::to_string(files.size()) + ".h5"));
      WriteBundle(bundle, files.back(), options);
    }
  }
  files.push_back(temp / "half_view_chunks.h5");
  WriteHalfViewChunkedSamples(bundle.light_field, files.back());

  for (const std::filesystem::path& path : files) {
    const Bundle whole = ReadBundle(path);
    const LightFieldShape& shape = whole.light_field.shape();
    for (const ViewBlock block : {ViewBlock{{0, 3}, 5, 1}, ViewBlock{{0, 1}, 5, 3}, ViewBlock{{1, 1}, 3, 3},
                                  ViewBlock{{2, 4}, 1, 1}, ViewBlock{{3, 0}, 2, 5}}) {
      BundleParts parts;
      parts.views = block;
      const Bundle part = ReadBundle(path, parts);
      LightFieldShape part_shape = shape;
      part_shape.nu = block.nu;
      part_shape.nv = block.nv;
      LightField expected(part_shape);
      CopyBlock(whole.light_field, block, expected);
      ExpectSameSamples(part.light_field, expected);
      ASSERT_EQ(part.light_field.HasWeights(), whole.light_field.HasWeights()) << path;
      if (whole.light_field.HasWeights()) {
        Array4D<float> weights(LightFieldShape{block.nu, block.nv, shape.width, shape.height, 1});
        CopyBlock(whole.light_field.weights(), block, weights);
        EXPECT_EQ(std::memcmp(part.light_field.weights().data(), weights.data(), weights.size() * sizeof(float)), 0)
            << path;
      }
      ASSERT_EQ(part.labels.has_value(), whole.labels.has_value()) << path;
      if (whole.labels) {
        Labels labels(LightFieldShape{block.nu, block.nv, shape.width, shape.height, 1});
        CopyBlock(*whole.labels, block, labels);
        EXPECT_EQ(std::memcmp(part.labels->data(), labels.data(), labels.size() * sizeof(std::int32_t)), 0) << path;
      }
      ASSERT_EQ(part.disparity.has_value(), whole.disparity.has_value()) << path;
      if (whole.disparity) {
        EXPECT_EQ(part.disparity->at(47, 63), whole.disparity->at(47, 63));
      }
    }
    EXPECT_EQ(ReadBundleShape(path), shape);
  }

  // Only what is asked for: labels alone leave the light field empty.
  BundleParts labels_only;
  labels_only.views = ViewBlock{{1, 1}, 3, 3};
  labels_only.samples = false;
  labels_only.disparity = false;
  const Bundle labels = ReadBundle(files.front(), labels_only);
  EXPECT_TRUE(labels.light_field.empty());
  EXPECT_FALSE(labels.disparity.has_value());
  ASSERT_TRUE(labels.labels.has_value());
  EXPECT_EQ(labels.labels->shape().nu, 3);
  // A block outside the views is refused, naming the file.
  BundleParts outside;
  outside.views = ViewBlock{{3, 3}, 3, 3};
  EXPECT_THROW((void)ReadBundle(files.front(), outside), Error);
}

TEST(Hdf5Bundle, SameContentGivesTheSameBytes) {
  TempDir temp;
  Bundle bundle;
  bundle.light_field = QuantisedLightField(8, 2);
  bundle.disparity = DisparityMap(64, 48, 0.5f);
  BundleWriteOptions options;
  options.compression_level = 6;
  WriteBundle(bundle, temp / "a.h5", options);
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // object timestamps have one-second resolution
  WriteBundle(bundle, temp / "b.h5", options);
  EXPECT_TRUE(lfsp::testing::ReadBytes(temp / "a.h5") == lfsp::testing::ReadBytes(temp / "b.h5"));
}

TEST(Pfm, WriteReadIsExactAndStoredBottomRowFirst) {
  TempDir temp;
  DisparityMap disparity(5, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) disparity.at(y, x) = static_cast<float>(10 * y + x) + 0.125f;
  WritePfm(disparity, temp / "d.pfm");
  const DisparityMap read = ReadPfm(temp / "d.pfm");
  ASSERT_EQ(read.width(), 5);
  ASSERT_EQ(read.height(), 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) EXPECT_EQ(read.at(y, x), disparity.at(y, x));

  // On disk: header "Pf\n5 3\n-1.0\n", then the bottom image row (y = 2) first, little-endian.
  const std::string bytes = lfsp::testing::ReadBytes(temp / "d.pfm");
  const std::string header = "Pf\n5 3\n-1.0\n";
  ASSERT_EQ(bytes.substr(0, header.size()), header);
  ASSERT_EQ(bytes.size(), header.size() + 5 * 3 * 4);
  float first = 0.0f;
  std::memcpy(&first, bytes.data() + header.size(), 4);
  EXPECT_EQ(first, disparity.at(2, 0));
}

TEST(HciConfig, ParsesSectionsNumbersAndText) {
  const Metadata config = ParseHciConfig(
      "[extrinsics]\nnum_cams_x = 9\nbaseline_mm = 100.0\n\n[meta]\ndisp_min = -3.3\ndate = 2017-03-20\n", "test.cfg");
  EXPECT_EQ(config["extrinsics"]["num_cams_x"].get<int>(), 9);
  EXPECT_DOUBLE_EQ(config["extrinsics"]["baseline_mm"].get<double>(), 100.0);
  EXPECT_DOUBLE_EQ(config["meta"]["disp_min"].get<double>(), -3.3);
  EXPECT_EQ(config["meta"]["date"].get<std::string>(), "2017-03-20");
  EXPECT_EQ(ParseHciConfig(FormatHciConfig(config), "again"), config);
  EXPECT_THROW(ParseHciConfig("[broken\n", "bad.cfg"), Error);
  EXPECT_THROW(ParseHciConfig("[a]\njust text\n", "bad.cfg"), Error);
}

TEST(SaveLightField, ViewsFolderCarriesTheDisparity) {
  TempDir temp;
  Bundle bundle;
  bundle.light_field = QuantisedLightField(8, 5);
  bundle.disparity = DisparityMap(64, 48, 0.75f);
  SaveLightField(bundle, temp / "out");
  const Bundle loaded = LoadLightField(temp / "out");
  ExpectSameSamples(bundle.light_field, loaded.light_field);
  ASSERT_TRUE(loaded.disparity.has_value());
  EXPECT_EQ(loaded.disparity->at(10, 10), 0.75f);
}

TEST(SaveLightField, RefusesToReplaceAFolderThatIsNotALightField) {
  TempDir temp;
  std::filesystem::create_directories(temp / "precious");
  lfsp::testing::WriteBytes(temp / "precious" / "thesis.tex", "do not delete");
  Bundle bundle;
  bundle.light_field = QuantisedLightField(8, 5);
  EXPECT_THROW(SaveLightField(bundle, temp / "precious"), Error);
  EXPECT_EQ(lfsp::testing::ReadBytes(temp / "precious" / "thesis.tex"), "do not delete");
}

}  // namespace
}  // namespace lfsp
