// Bad input gives lfsp::Error naming the file and the problem; `lfsp info` prints one line and exits 2 (issue 2).

#include <H5Cpp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "lfsp/core/conventions.h"
#include "lfsp/core/error.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/utf8.h"
#include "lfsp/core/views_folder.h"
#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using lfsp::testing::ReadBytes;
using lfsp::testing::RunLfsp;
using lfsp::testing::TempDir;
using lfsp::testing::WriteBytes;

void WriteSmallViewsFolder(const fs::path& folder) {
  LightField light_field({3, 3, 16, 12, 3});
  for (std::size_t i = 0; i < light_field.size(); ++i) light_field.data()[i] = static_cast<float>(i % 255) / 255.0f;
  WriteViewsFolder(light_field, folder);
}

// Runs `load` expecting lfsp::Error whose message contains every fragment.
template <typename Load>
void ExpectErrorMentioning(Load load, const std::vector<std::string>& fragments) {
  try {
    load();
    ADD_FAILURE() << "expected lfsp::Error";
  } catch (const Error& error) {
    const std::string message = error.what();
    for (const auto& fragment : fragments)
      EXPECT_NE(message.find(fragment), std::string::npos) << "message '" << message << "' lacks '" << fragment << "'";
  }
}

// `lfsp info PATH` must exit 2 with exactly one line on stderr naming the file.
void ExpectInfoFailsCleanly(const fs::path& path, const std::string& named) {
  const auto result = RunLfsp({"info", path.string()});
  EXPECT_EQ(result.exit_status, 2) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_EQ(result.err.rfind("lfsp: error: ", 0), 0u) << result.err;
  EXPECT_NE(result.err.find(named), std::string::npos) << result.err;
}

TEST(BadInput, TruncatedPngView) {
  TempDir temp;
  WriteSmallViewsFolder(temp / "lf");
  const fs::path view = temp / "lf" / "input_Cam004.png";
  const std::string bytes = ReadBytes(view);
  WriteBytes(view, bytes.substr(0, bytes.size() / 2));
  ExpectErrorMentioning([&] { ReadViewsFolder(temp / "lf"); }, {"input_Cam004.png"});
  ExpectInfoFailsCleanly(temp / "lf", "input_Cam004.png");
}

TEST(BadInput, MissingView) {
  TempDir temp;
  WriteSmallViewsFolder(temp / "lf");
  fs::remove(temp / "lf" / "input_Cam007.png");
  ExpectErrorMentioning([&] { ReadViewsFolder(temp / "lf"); }, {"input_Cam007.png", "missing"});
  ExpectInfoFailsCleanly(temp / "lf", "input_Cam007.png");
}

TEST(BadInput, ViewsOfDifferentSizes) {
  TempDir temp;
  WriteSmallViewsFolder(temp / "lf");
  WriteImage(cv::Mat(12, 15, CV_32FC3, cv::Scalar::all(0.5)), temp / "lf" / "input_Cam002.png");
  ExpectErrorMentioning([&] { ReadViewsFolder(temp / "lf"); }, {"input_Cam002.png", "15x12", "16x12"});
  ExpectInfoFailsCleanly(temp / "lf", "input_Cam002.png");
}

// HCI weight_Cam### files are ray weights of the view with the same camera number. Only their count was checked, so
// weight_Cam001..009 beside input_Cam000..008 gave every view the next camera's weights without a word.
TEST(BadInput, HciWeightsPairedByCameraNumber) {
  TempDir temp;
  LightField light_field({3, 3, 16, 12, 3});
  std::fill(light_field.data(), light_field.data() + light_field.size(), 0.5f);
  light_field.EnableWeights();
  for (int camera = 0; camera < 9; ++camera) {
    float* weights = light_field.weights().ViewData(ViewFromCameraNumber(camera, 3));
    std::fill(weights, weights + 16 * 12, 0.1f * static_cast<float>(camera + 1));
  }
  WriteViewsFolder(light_field, temp / "lf");
  const auto weight = [&](int camera) { return temp / "lf" / ("weight_Cam00" + std::to_string(camera) + ".png"); };

  const LightField read = ReadViewsFolder(temp / "lf");
  ASSERT_TRUE(read.HasWeights());
  for (int camera = 0; camera < 9; ++camera)
    EXPECT_NEAR(read.weights().ViewData(ViewFromCameraNumber(camera, 3))[0], 0.1f * static_cast<float>(camera + 1),
                1e-4f)
        << "camera " << camera;

  // Numbered from 1: camera 0 has no weight, and weight_Cam009 no view.
  fs::copy(temp / "lf", temp / "shifted");
  for (int camera = 8; camera >= 0; --camera)
    fs::rename(temp / "shifted" / weight(camera).filename(), temp / "shifted" / weight(camera + 1).filename());
  ExpectErrorMentioning([&] { ReadViewsFolder(temp / "shifted"); }, {"shifted", "input_Cam000.png", "no weight"});
  ExpectInfoFailsCleanly(temp / "shifted", "input_Cam000.png");

  fs::copy(temp / "lf", temp / "missing");
  fs::remove(temp / "missing" / weight(4).filename());
  ExpectErrorMentioning([&] { ReadViewsFolder(temp / "missing"); }, {"missing", "input_Cam004.png", "no weight"});

  fs::copy(temp / "lf", temp / "extra");
  fs::copy_file(weight(8), temp / "extra" / weight(9).filename());
  ExpectErrorMentioning([&] { ReadViewsFolder(temp / "extra"); }, {"extra", "weight_Cam009.png", "no view"});
  ExpectInfoFailsCleanly(temp / "extra", "weight_Cam009.png");
}

// A <row>_<col> folder of noise views in `extension`, with view (row 2, column 2) replaced by the first `keep` of
// its bytes (a fraction of the file).
fs::path ViewsFolderWithACutView(const TempDir& temp, const std::string& name, const std::string& extension,
                                 double keep) {
  const fs::path folder = temp / name;
  fs::create_directories(folder);
  cv::RNG random(7);
  for (int row = 1; row <= 3; ++row)
    for (int column = 1; column <= 3; ++column) {
      cv::Mat view(64, 80, CV_32FC3);
      random.fill(view, cv::RNG::UNIFORM, 0.0f, 1.0f);
      WriteImage(view, folder / (std::to_string(row) + "_" + std::to_string(column) + extension));
    }
  const fs::path cut = folder / ("2_2" + extension);
  const std::string bytes = ReadBytes(cut);
  WriteBytes(cut, bytes.substr(0, static_cast<std::size_t>(static_cast<double>(bytes.size()) * keep)));
  return cut;
}

// libjpeg decodes a truncated JPEG to the end, filling what is missing with grey, and only warns; OpenImageIO records
// the warning but reports the read as done. `lfsp convert` wrote such a folder with exit status 0.
TEST(BadInput, TruncatedOrCorruptJpegView) {
  TempDir temp;
  const fs::path cut = ViewsFolderWithACutView(temp, "jpeg", ".jpg", 0.4);
  ExpectErrorMentioning([&] { ReadViewsFolder(temp / "jpeg"); }, {cut.string(), "truncated or corrupt"});
  ExpectInfoFailsCleanly(temp / "jpeg", "2_2.jpg");
  const auto convert = RunLfsp({"convert", (temp / "jpeg").string(), (temp / "out.h5").string()});
  EXPECT_EQ(convert.exit_status, 2) << convert.err;
  EXPECT_EQ(std::count(convert.err.begin(), convert.err.end(), '\n'), 1) << convert.err;
  EXPECT_NE(convert.err.find("2_2.jpg"), std::string::npos) << convert.err;
  EXPECT_FALSE(fs::exists(temp / "out.h5"));

  // Whole, but with an end-of-image marker in the middle of the compressed data.
  const fs::path corrupt = ViewsFolderWithACutView(temp, "corrupt", ".jpg", 1.0);
  std::string bytes = ReadBytes(corrupt);
  bytes[bytes.size() / 2] = '\xFF';
  bytes[bytes.size() / 2 + 1] = '\xD9';
  WriteBytes(corrupt, bytes);
  ExpectErrorMentioning([&] { ReadViewsFolder(temp / "corrupt"); }, {corrupt.string(), "truncated or corrupt"});

  // A progressive JPEG is decoded whole while it is opened: its damage is recorded then, not by the read.
  const fs::path progressive = ViewsFolderWithACutView(temp, "progressive", ".jpg", 1.0);
  cv::Mat noise(64, 80, CV_8UC3);
  cv::RNG(3).fill(noise, cv::RNG::UNIFORM, 0, 256);
  ASSERT_TRUE(cv::imwrite(progressive.string(), noise, {cv::IMWRITE_JPEG_PROGRESSIVE, 1}));
  const std::string whole = ReadBytes(progressive);
  WriteBytes(progressive, whole.substr(0, whole.size() * 2 / 5));
  ExpectErrorMentioning([&] { ReadViewsFolder(temp / "progressive"); }, {progressive.string(), "truncated or corrupt"});

  // PNG and TIFF views cut short were refused already (the PNG's chunks, libtiff's strips); they stay refused.
  for (const std::string extension : {".png", ".tif"}) {
    const std::string name = "cut_" + extension.substr(1);
    const fs::path other = ViewsFolderWithACutView(temp, name, extension, 0.6);
    ExpectErrorMentioning([&] { ReadViewsFolder(temp / name); }, {other.string()});
    ExpectInfoFailsCleanly(temp / name, other.string());
  }
}

// A parameters.cfg value lfsp cannot use is the file's fault: the message names it (it named neither file nor folder).
TEST(BadInput, UnusableParametersCfgNamesTheFile) {
  TempDir temp;
  WriteSmallViewsFolder(temp / "lf");
  const fs::path config = temp / "lf" / "parameters.cfg";
  const std::string cams = "[extrinsics]\nnum_cams_x = 3\nnum_cams_y = 3\n\n";

  WriteBytes(config, cams + "[lfsp]\ntransfer = bogus\n");
  ExpectErrorMentioning([&] { ReadViewsFolder(temp / "lf"); }, {config.string(), "transfer", "'bogus'", "srgb"});
  ExpectInfoFailsCleanly(temp / "lf", config.string());
  WriteBytes(config, cams + "[lfsp]\ntransfer = 1\n");  // not a name at all: was read as sRGB
  ExpectErrorMentioning([&] { ReadViewsFolder(temp / "lf"); }, {config.string(), "transfer", "1"});

  WriteBytes(config, cams + "[meta]\ndisp_min = nan\ndisp_max = 2.8\n");
  ExpectErrorMentioning([&] { LoadLightField(temp / "lf"); }, {config.string(), "disp_min = nan", "not a finite"});
  ExpectInfoFailsCleanly(temp / "lf", config.string());
  WriteBytes(config, cams + "[meta]\ndisp_min = -3.3\ndisp_max = -inf\n");
  ExpectErrorMentioning([&] { LoadLightField(temp / "lf"); }, {config.string(), "disp_max = -inf"});
}

// A parameters.cfg that is not UTF-8 text is refused with its line: its values become metadata, which nothing can write
// otherwise (fuzz finding: a non-UTF-8 num_cams_x ended FindViewsLayout with nlohmann's type_error, and a Latin-1
// "authors = Müller" made `lfsp info` and `lfsp convert` internal failures).
TEST(BadInput, ParametersCfgThatIsNotUtf8NamesTheLine) {
  TempDir temp;
  WriteSmallViewsFolder(temp / "lf");
  const fs::path config = temp / "lf" / "parameters.cfg";

  WriteBytes(config, "[extrinsics]\nnum_cams_x = \xff\nnum_cams_y = 3\n");
  ExpectErrorMentioning([&] { ReadViewsFolder(temp / "lf"); },
                        {config.string(), "line 2 is not UTF-8", "0xFF", "column 14"});
  ExpectInfoFailsCleanly(temp / "lf", config.string());

  WriteBytes(config, "[extrinsics]\nnum_cams_x = 3\nnum_cams_y = 3\n\n[meta]\nauthors = M\xfcller\n");
  ExpectErrorMentioning([&] { LoadLightField(temp / "lf"); }, {config.string(), "line 6 is not UTF-8", "0xFC"});
  ExpectInfoFailsCleanly(temp / "lf", config.string());
  const auto convert = RunLfsp({"convert", (temp / "lf").string(), (temp / "lf.h5").string()});
  EXPECT_EQ(convert.exit_status, 2) << convert.err;

  // UTF-8 itself is kept as it is, and written back.
  WriteBytes(config, "[extrinsics]\nnum_cams_x = 3\nnum_cams_y = 3\n\n[meta]\nauthors = M\xc3\xbcller\n");
  EXPECT_EQ(LoadLightField(temp / "lf").light_field.metadata["meta"]["authors"], "M\xc3\xbcller");
  const auto written = RunLfsp({"convert", (temp / "lf").string(), (temp / "utf8.h5").string()});
  EXPECT_EQ(written.exit_status, 0) << written.err;
  EXPECT_EQ(FirstNonUtf8Byte("ab\xc3\xbc\xed\xa0\x80"), 4u);  // a surrogate is not UTF-8
  EXPECT_EQ(FirstNonUtf8Byte("ab\xc3\xbc"), std::string::npos);
}

// The old HCI layout's labels.h5 beside an lf.h5 without labels: its problems name it, not the bundle (fuzz finding,
// core/fuzz_hci_labels: one that was not HDF5 was reported as "lf.h5: HDF5 read failed in H5File constructor").
TEST(BadInput, SiblingLabelsH5NamesItself) {
  TempDir temp;
  Bundle bundle;
  bundle.light_field = LightField({3, 3, 8, 6, 3});
  WriteBundle(bundle, temp / "lf.h5");
  const fs::path labels = temp / "labels.h5";

  WriteBytes(labels, "GT_LABELS\n");
  ExpectErrorMentioning([&] { ReadBundle(temp / "lf.h5"); }, {labels.string(), "not an HDF5 file"});
  ExpectInfoFailsCleanly(temp / "lf.h5", labels.string());

  {  // HDF5, with GT_LABELS of floats
    H5::H5File file(labels.string(), H5F_ACC_TRUNC);
    const hsize_t dims[4] = {3, 3, 6, 8};
    file.createDataSet("GT_LABELS", H5::PredType::NATIVE_FLOAT, H5::DataSpace(4, dims));
  }
  ExpectErrorMentioning([&] { ReadBundle(temp / "lf.h5"); }, {labels.string(), "GT_LABELS", "integers"});
}

// Tiny chunks over a large declared shape: libhdf5 keeps a record of each chunk a read covers, so 196,599 chunks in a
// 5 KB labels.h5 took 1.3 GB (fuzz finding, core/fuzz_hci_labels). The chunk count is held to the declared-size rule.
TEST(BadInput, Hdf5WithMillionsOfTinyChunksIsRefused) {
  TempDir temp;
  const fs::path labels = temp / "labels.h5";
  {
    H5::H5File file(labels.string(), H5F_ACC_TRUNC);
    const hsize_t dims[4] = {65533, 3, 6, 8};
    const hsize_t chunk[4] = {1, 1, 6, 8};
    H5::DSetCreatPropList properties;
    properties.setChunk(4, chunk);
    file.createDataSet("GT_LABELS", H5::PredType::STD_U16LE, H5::DataSpace(4, dims), properties);
  }
  ASSERT_LT(fs::file_size(labels), 10000u);
  ExpectErrorMentioning([&] { ReadLabels(labels); }, {labels.string(), "GT_LABELS", "196599 chunks", "not plausible"});
}

TEST(BadInput, GarbagePfmHeader) {
  TempDir temp;
  WriteBytes(temp / "garbage.pfm", "P7\nhello world\n\x01\x02");
  ExpectErrorMentioning([&] { ReadPfm(temp / "garbage.pfm"); }, {"garbage.pfm", "not a PFM"});
  ExpectInfoFailsCleanly(temp / "garbage.pfm", "garbage.pfm");

  WriteBytes(temp / "size.pfm", "Pf\n-4 abc\n-1.0\n");
  ExpectErrorMentioning([&] { ReadPfm(temp / "size.pfm"); }, {"size.pfm", "width"});

  WriteBytes(temp / "short.pfm", "Pf\n4 4\n-1.0\n" + std::string(20, '\0'));
  ExpectErrorMentioning([&] { ReadPfm(temp / "short.pfm"); }, {"short.pfm", "truncated", "64"});
}

// A message that quotes a file's bytes stays one printable, valid UTF-8 line: an HDF5 file read as PFM quoted its
// magic's byte 0x89 raw, which the terminal showed as garbage and Python could not turn into the message at all.
TEST(BadInput, MessagesQuoteBinaryBytesAsEscapes) {
  TempDir temp;
  WriteBytes(temp / "bundle.pfm", std::string("\x89HDF\r\n\x1a\n") + std::string(16, '\0'));
  ExpectErrorMentioning([&] { ReadPfm(temp / "bundle.pfm"); }, {"bundle.pfm", "not a PFM", "\\x89HDF"});
  const auto info = RunLfsp({"info", (temp / "bundle.pfm").string()});
  EXPECT_EQ(info.exit_status, 2);
  EXPECT_EQ(std::count(info.err.begin(), info.err.end(), '\n'), 1) << info.err;
  EXPECT_EQ(info.err.find('\x89'), std::string::npos) << info.err;

  EXPECT_EQ(PrintableText("caf\xC3\xA9 \xE2\x82\xAC"), "caf\xC3\xA9 \xE2\x82\xAC");  // valid UTF-8 is kept
  EXPECT_EQ(PrintableText("a\nb\tc"), "a\\x0Ab\\x09c");
  EXPECT_EQ(PrintableText("\xC3(\xE2\x82"), "\\xC3(\\xE2\\x82");                  // broken sequences
  EXPECT_EQ(PrintableText("\xED\xA0\x80\xC0\xAF"), "\\xED\\xA0\\x80\\xC0\\xAF");  // a surrogate, an overlong form
  EXPECT_STREQ(Error("x\x89y").what(), "x\\x89y");
}

TEST(BadInput, Hdf5WithoutLightField) {
  TempDir temp;
  const fs::path path = temp / "nolf.h5";
  {
    H5::H5File file(path.string(), H5F_ACC_TRUNC);
    const hsize_t dims[1] = {4};
    const int values[4] = {1, 2, 3, 4};
    file.createDataSet("something_else", H5::PredType::NATIVE_INT, H5::DataSpace(1, dims))
        .write(values, H5::PredType::NATIVE_INT);
  }
  ExpectErrorMentioning([&] { ReadBundle(path); }, {"nolf.h5", "LF"});
  ExpectInfoFailsCleanly(path, "nolf.h5");
}

TEST(BadInput, FilesThatAreNotWhatTheirNameSays) {
  TempDir temp;
  WriteBytes(temp / "fake.h5", "this is not hdf5");
  ExpectErrorMentioning([&] { ReadBundle(temp / "fake.h5"); }, {"fake.h5", "not an HDF5"});
  ExpectInfoFailsCleanly(temp / "fake.h5", "fake.h5");
  ExpectErrorMentioning([&] { LoadLightField(temp / "absent"); }, {"absent", "no such"});
  fs::create_directories(temp / "empty");
  ExpectErrorMentioning([&] { LoadLightField(temp / "empty"); }, {"empty", "no light-field views"});
}

TEST(BadInput, FailedWriteLeavesNothingBehind) {
  TempDir temp;
  LightField light_field({2, 2, 8, 8, 3});
  // Bit depth 12 is refused part-way; the destination must not appear, nor any temporary.
  ViewsFolderOptions options;
  options.bit_depth = 12;
  EXPECT_THROW(WriteViewsFolder(light_field, temp / "out", options), Error);
  EXPECT_TRUE(fs::is_empty(temp.path()));
}

TEST(Cli, UnknownOptionIsBadInput) {
  const auto result = RunLfsp({"info", "--no-such-option", "x"});
  EXPECT_EQ(result.exit_status, 2);
  EXPECT_EQ(result.err.rfind("lfsp: error: ", 0), 0u) << result.err;
}

TEST(Cli, HelpAndVersion) {
  const auto help = RunLfsp({"--help"});
  EXPECT_EQ(help.exit_status, 0);
  EXPECT_NE(help.out.find("info"), std::string::npos);
  const auto version = RunLfsp({"--version"});
  EXPECT_EQ(version.exit_status, 0);
  EXPECT_NE(version.out.find("lfsp "), std::string::npos);
}

}  // namespace
}  // namespace lfsp
