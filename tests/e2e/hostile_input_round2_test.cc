// Hostile input, second round (issue 45): one test per row of the issue's table. Each input broke the promise on
// main at 7cd43f3 (a signal, a hang, exit 1 for bad input, or files left behind); each must now exit 0, or exit 2
// with one line naming the culprit and nothing left behind.

#include <H5Cpp.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/light_field.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/views_folder.h"
#include "lfsp/decode/lfp_container.h"
#include "refusal.h"
#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::ReadBytes;
using testing::RunLfsp;
using testing::SourceDir;
using testing::TempDir;
using testing::WriteBytes;

using testing::ExpectRefused;

// Everything in `folder` (recursively) whose name is not in `inputs`: what a refused command left behind.
std::vector<std::string> LeftBehind(const fs::path& folder, const std::vector<std::string>& inputs) {
  std::vector<std::string> left;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    const fs::path relative = fs::relative(entry.path(), folder);
    const std::string top = relative.begin()->string();
    if (std::find(inputs.begin(), inputs.end(), top) == inputs.end()) left.push_back(relative.string());
  }
  return left;
}

LightField SmallLightField(int n, int width, int height) {
  LightField light_field({n, n, width, height, 3});
  for (std::size_t i = 0; i < light_field.size(); ++i)
    light_field.data()[i] = static_cast<float>((i * 37) % 251) / 251.0f;
  return light_field;
}

// A 3x3-view bundle (16x12 views, zero disparity) whose metadata attribute is `metadata`, written as given (the
// outside run made it with h5py; lfsp's writer would not write text that is not its own JSON). The newest file
// format, so that an attribute over 64 KiB fits.
void WriteBundleWithMetadataText(const fs::path& path, const std::string& metadata) {
  H5::FileAccPropList access;
  H5Pset_libver_bounds(access.getId(), H5F_LIBVER_LATEST, H5F_LIBVER_LATEST);
  H5::H5File file(path.string(), H5F_ACC_TRUNC, H5::FileCreatPropList::DEFAULT, access);
  const LightField light_field = SmallLightField(3, 16, 12);
  const hsize_t lf_dims[5] = {3, 3, 12, 16, 3};
  file.createDataSet("LF", H5::PredType::IEEE_F32LE, H5::DataSpace(5, lf_dims))
      .write(light_field.data(), H5::PredType::NATIVE_FLOAT);
  const std::vector<float> disparity(16 * 12, 0.0f);
  const hsize_t disparity_dims[2] = {12, 16};
  file.createDataSet("disparity", H5::PredType::IEEE_F32LE, H5::DataSpace(2, disparity_dims))
      .write(disparity.data(), H5::PredType::NATIVE_FLOAT);
  const H5::StrType type(H5::PredType::C_S1, metadata.size());
  file.createAttribute("metadata", type, H5::DataSpace(H5S_SCALAR)).write(type, metadata);
}

std::string Nested(int depth) { return std::string(static_cast<std::size_t>(depth), '[') + std::string(depth, ']'); }

// Rows 1 and 2: 200,000 nested '[' as bundle metadata overflowed the stack in info, depth and convert (convert also
// left its *.tmp-*.h5 behind).
TEST(HostileInputRound2, DeeplyNestedBundleMetadata) {
  const TempDir temp;
  WriteBundleWithMetadataText(temp / "nested.h5", Nested(200000));
  const std::string input = (temp / "nested.h5").string();
  ExpectRefused(RunLfsp({"info", input}), "nested more than 100 levels");
  ExpectRefused(RunLfsp({"depth", input, "--dmin", "-1", "--dmax", "1", "--out", (temp / "d.pfm").string()}), input);
  ExpectRefused(RunLfsp({"convert", input, (temp / "out.h5").string()}), input);
  EXPECT_EQ(LeftBehind(temp.path(), {"nested.h5"}), std::vector<std::string>{});
}

// Rows 3 and 4: metadata that is JSON but not an object reached code that indexes it by key (nlohmann type_error
// 305, exit 1) after segment had written its planes and overlays.
TEST(HostileInputRound2, BundleMetadataThatIsNotAnObject) {
  const TempDir temp;
  for (const std::string& metadata : {std::string("[1,2]"), std::string("\"hello\""), Nested(5000)}) {
    SCOPED_TRACE(metadata.substr(0, 16));
    WriteBundleWithMetadataText(temp / "lf.h5", metadata);
    ExpectRefused(RunLfsp({"segment", (temp / "lf.h5").string(), "--size", "8", "--out", (temp / "s.h5").string()}),
                  "attribute 'metadata'");
    EXPECT_EQ(LeftBehind(temp.path(), {"lf.h5"}), std::vector<std::string>{});
  }
}

// Row 5: a view that is a FIFO made info, depth and view wait forever for a writer.
TEST(HostileInputRound2, ViewThatIsAFifo) {
  const TempDir temp;
  WriteViewsFolder(SmallLightField(3, 16, 12), temp / "views");
  const fs::path fifo = temp / "views" / "input_Cam004.png";
  fs::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string input = (temp / "views").string();
  ExpectRefused(RunLfsp({"info", input}), "input_Cam004.png: not a regular file");
  ExpectRefused(RunLfsp({"depth", input, "--dmin", "-1", "--dmax", "1", "--out", (temp / "d.pfm").string()}),
                "input_Cam004.png: not a regular file");
  ExpectRefused(RunLfsp({"view", input, "--port", "0"}), "input_Cam004.png: not a regular file");
  EXPECT_EQ(LeftBehind(temp.path(), {"views"}), std::vector<std::string>{});
}

// Row 6: a 48x48 map of 3e38 corrupted the heap (SIGABRT "double free or corruption"). Its plane fits were not
// finite, so no centre pixel landed in any side view; those views kept the placeholder label -1, which the refinement
// used as a superpixel index. A map whose scaled values overflow SLIC's float distances is now refused; a map of
// +-3e38 steps that SLIC can compare (its range overflows, so the channel scales to 0) segments.
TEST(HostileInputRound2, DisparityMapOfTheLargestFloats) {
  const TempDir temp;
  Bundle bundle;
  bundle.light_field = SmallLightField(3, 48, 48);
  WriteBundle(bundle, temp / "lf.h5");
  WritePfm(DisparityMap(48, 48, 3e38f), temp / "huge.pfm");
  ExpectRefused(RunLfsp({"segment", (temp / "lf.h5").string(), "--disparity", (temp / "huge.pfm").string(), "--out",
                         (temp / "s.h5").string()}),
                "disparities are too large to segment");
  EXPECT_EQ(LeftBehind(temp.path(), {"lf.h5", "huge.pfm"}), std::vector<std::string>{});

  DisparityMap step(48, 48);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; ++x) step.at(y, x) = x < 24 ? 3e38f : -3e38f;
  WritePfm(step, temp / "step.pfm");
  const CommandResult stepped = RunLfsp({"segment", (temp / "lf.h5").string(), "--disparity",
                                         (temp / "step.pfm").string(), "--out", (temp / "step.h5").string()});
  EXPECT_EQ(stepped.exit_status, 0) << stepped.err;
  EXPECT_TRUE(ReadBundle(temp / "step.h5").labels.has_value());
}

// Row 7: refocus levels of +-1e9 in `evaluate segmentation` corrupted the heap the same way (every refocused ray
// leaves the view). Levels beyond +-1000 px are refused before the bundle is read, as `refocus --disparities` is;
// +-1000 itself, where still nothing lands in a side view, is evaluated.
TEST(HostileInputRound2, RefocusLevelsFarOutsideTheViews) {
  const TempDir temp;
  Bundle bundle;
  bundle.light_field = SmallLightField(3, 48, 48);
  bundle.disparity = DisparityMap(48, 48, 0.0f);
  WriteBundle(bundle, temp / "lf.h5");
  ASSERT_EQ(
      RunLfsp({"segment", (temp / "lf.h5").string(), "--size", "8", "--out", (temp / "s.h5").string()}).exit_status, 0);
  ExpectRefused(RunLfsp({"evaluate", "segmentation", (temp / "s.h5").string(), "--refocus-levels", "1e9,-1e9"}),
                "--refocus-levels");
  const CommandResult edge =
      RunLfsp({"evaluate", "segmentation", (temp / "s.h5").string(), "--refocus-levels", "1000,-1000"});
  EXPECT_EQ(edge.exit_status, 0) << edge.err;
}

// Row 15: bytes flipped inside the zlib stream of a compressed v5 .mat read back as a mostly-zero light field.
TEST(HostileInputRound2, MatWithACorruptZlibStream) {
  const TempDir temp;
  Bundle bundle;
  bundle.light_field = SmallLightField(3, 16, 12);
  WriteBundle(bundle, temp / "lf.h5");
  ASSERT_EQ(RunLfsp({"convert", (temp / "lf.h5").string(), (temp / "good.mat").string()}).exit_status, 0);
  std::string bytes = ReadBytes(temp / "good.mat");
  // The light field's miCOMPRESSED element starts after the 128-byte header; flip bytes well inside its stream.
  ASSERT_GT(bytes.size(), 1200u);
  for (std::size_t i = 600; i < 616; ++i) bytes[i] = static_cast<char>(bytes[i] ^ 0xA5);
  WriteBytes(temp / "bad.mat", bytes);
  fs::remove(temp / "good.mat");
  fs::remove(temp / "lf.h5");
  const std::string input = (temp / "bad.mat").string();
  ExpectRefused(RunLfsp({"info", input}), "bad.mat: compressed variable at byte 128");
  ExpectRefused(RunLfsp({"convert", input, (temp / "out.h5").string()}), "bad.mat");
  ExpectRefused(RunLfsp({"refocus", input, "--disparities", "0.5", "--out", (temp / "r").string()}), "bad.mat");
  EXPECT_EQ(LeftBehind(temp.path(), {"bad.mat"}), std::vector<std::string>{});
}

// Rows 10 and 11: simulate options refused only after writing (the capture, white images and geometry for an
// infinite disparity scale; an empty folder for a huge size or a NaN exposure).
TEST(HostileInputRound2, SimulateOptionsRefusedBeforeWriting) {
  const TempDir temp;
  const std::string out = (temp / "sim").string();
  ExpectRefused(RunLfsp({"simulate", "--camera", "mini-f01", "--disparity-scale", "inf", "--out", out}),
                "disparity scale");
  ExpectRefused(RunLfsp({"simulate", "--ideal-only", "--size", "100000x100000", "--out", out}), "view size");
  ExpectRefused(RunLfsp({"simulate", "--exposure", "nan", "--out", out}), "exposure");
  EXPECT_FALSE(fs::exists(out));
}

// Row 12: a scene of thousands of objects made the bundle's metadata attribute larger than the oldest HDF5 format
// holds (64 KiB); H5Acreate2 failed and the failure was reported as bad input.
TEST(HostileInputRound2, SceneWhoseMetadataExceeds64KiB) {
  const TempDir temp;
  nlohmann::json scene = nlohmann::json::parse(ReadBytes(SourceDir() / "samples" / "ideal" / "scene.json"));
  const nlohmann::json object = scene["objects"][0];
  for (int i = 0; i < 2000; ++i) scene["objects"].push_back(object);
  WriteBytes(temp / "scene.json", scene.dump());
  const fs::path out = temp / "sim";
  const CommandResult result =
      RunLfsp({"simulate", "--scene", (temp / "scene.json").string(), "--ideal-only", "--views", "3", "--size", "16x12",
               "--supersampling", "1", "--out", out.string()});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const Bundle written = ReadBundle(out / "ideal.h5");
  EXPECT_GT(written.light_field.metadata["simulate"]["scene_json"].get<std::string>().size(), 65536u);
}

// Row 13: an EPI row outside the views was refused after the whole segmentation, an overlay left behind.
TEST(HostileInputRound2, EpiRowOutsideTheViews) {
  const TempDir temp;
  Bundle bundle;
  bundle.light_field = SmallLightField(3, 32, 24);
  bundle.disparity = DisparityMap(32, 24, 0.0f);
  WriteBundle(bundle, temp / "lf.h5");
  for (const char* option : {"--epi-row", "--epi-column"}) {
    ExpectRefused(RunLfsp({"segment", (temp / "lf.h5").string(), "--size", "8", option, "100000", "--out",
                           (temp / "s.h5").string()}),
                  option);
    EXPECT_EQ(LeftBehind(temp.path(), {"lf.h5"}), std::vector<std::string>{});
  }
}

// Row 14: `noise-study --exposures 0` was refused after 6 s of rendering, captures/exposure_0.000000/ left.
TEST(HostileInputRound2, NoiseStudyExposureRefusedBeforeWork) {
  const TempDir temp;
  const fs::path out = temp / "study";
  for (const char* exposures : {"0", "0.7,nan", "0.7,5"}) {
    SCOPED_TRACE(exposures);
    ExpectRefused(RunLfsp({"noise-study", "--camera", "mini-illum", "--views", "3", "--width", "32", "--height", "32",
                           "--exposures", exposures, "--out", out.string()}),
                  "--exposures");
    EXPECT_FALSE(fs::exists(out));
  }
}

// Rows 8 and 9: containers that make `info --extract` write without bound. The bundled F01 capture's table of
// contents is rewritten to list its one frame `copies` times (every SHA-1 valid), and `empty_sections` empty
// sections are appended.
fs::path HostileF01Capture(const fs::path& folder, int copies, int empty_sections) {
  decode::LfpContainer container = decode::ReadLfpContainer(SourceDir() / "samples" / "mini-f01" / "capture.lfp");
  decode::LfpSection& toc = container.sections.front();
  nlohmann::json contents = nlohmann::json::parse(toc.Text());
  const nlohmann::json frame = contents["picture"]["frameArray"][0];
  for (int i = 1; i < copies; ++i) contents["picture"]["frameArray"].push_back(frame);
  const std::string text = contents.dump(1, '\t');
  toc.payload.assign(text.begin(), text.end());
  for (int i = 0; i < empty_sections; ++i) container.AddBinary({});
  const fs::path path = folder / "capture.lfp";
  decode::WriteLfpContainer(container, path);
  return path;
}

std::uintmax_t BytesUnder(const fs::path& folder) {
  std::uintmax_t bytes = 0;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.is_regular_file()) bytes += entry.file_size();
  return bytes;
}

TEST(HostileInputRound2, ExtractWritesEachPayloadOnce) {
  const TempDir temp;
  const fs::path capture = HostileF01Capture(temp.path(), 40, 0);
  const CommandResult result = RunLfsp({"info", capture.string(), "--extract", (temp / "out").string()});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  // The raw frame once (1.5 MB), not 40 times (60 MB); the JSON descriptions beside it are small.
  EXPECT_LT(BytesUnder(temp / "out"), 2 * fs::file_size(capture));
}

TEST(HostileInputRound2, ExtractSkipsEmptySectionsAndBuildsItsFolderWhole) {
  const TempDir temp;
  const fs::path capture = HostileF01Capture(temp.path(), 1, 2000);
  const CommandResult result = RunLfsp({"info", capture.string(), "--extract", (temp / "out").string()});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const auto files = std::distance(fs::directory_iterator(temp / "out"), fs::directory_iterator());
  EXPECT_LT(files, 20) << "empty sections hold nothing to extract";
  EXPECT_TRUE(fs::exists(temp / "out" / "manifest.json"));
  EXPECT_EQ(LeftBehind(temp.path(), {"capture.lfp", "out"}), std::vector<std::string>{});

  // The folder is replaced whole, and only when it holds an earlier extraction.
  fs::create_directories(temp / "mine");
  WriteBytes(temp / "mine" / "notes.txt", "not an extraction");
  ExpectRefused(RunLfsp({"info", capture.string(), "--extract", (temp / "mine").string()}), "holds no earlier");
  EXPECT_TRUE(fs::exists(temp / "mine" / "notes.txt"));
}

// The issue's three accepted cases, decided: samples of -5 are light values every stage computes with (kept); a
// negative ray weight is no weight (refused); a declared disparity range that is not numbers is garbage (refused).
TEST(HostileInputRound2, AcceptedCasesDecided) {
  const TempDir temp;
  Bundle bundle;
  bundle.light_field = SmallLightField(3, 16, 12);
  bundle.light_field.data()[5] = -5.0f;
  WriteBundle(bundle, temp / "negative_sample.h5", {SampleStorage::kFloat32, 0});
  const CommandResult negative_sample = RunLfsp({"info", (temp / "negative_sample.h5").string()});
  EXPECT_EQ(negative_sample.exit_status, 0) << negative_sample.err;

  bundle.light_field.data()[5] = 0.5f;
  bundle.light_field.EnableWeights();
  std::fill(bundle.light_field.weights().data(),
            bundle.light_field.weights().data() + bundle.light_field.weights().size(), 1.0f);
  bundle.light_field.weights().data()[7] = -0.25f;
  WriteBundle(bundle, temp / "negative_weight.h5", {SampleStorage::kFloat32, 0});
  ExpectRefused(RunLfsp({"info", (temp / "negative_weight.h5").string()}), "negative ray weight");

  WriteBundleWithMetadataText(temp / "low.h5", R"({"meta": {"disp_min": "low", "disp_max": 2}})");
  ExpectRefused(RunLfsp({"info", (temp / "low.h5").string()}), "meta.disp_min");
}

}  // namespace
}  // namespace lfsp
