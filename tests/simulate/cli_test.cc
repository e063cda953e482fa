// `lfsp simulate` end to end: deterministic outputs, bad input, and the bundled samples are loadable and up to date.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/load.h"
#include "lfsp/decode/lytro_capture.h"
#include "lfsp/simulate/lenslet_camera.h"
#include "png_bytes.h"
#include "test_support.h"

namespace lfsp::simulate {
namespace {

std::vector<std::filesystem::path> FilesUnder(const std::filesystem::path& root) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root))
    if (entry.is_regular_file()) files.push_back(std::filesystem::relative(entry.path(), root));
  std::sort(files.begin(), files.end());
  return files;
}

void ExpectSameBundle(const std::filesystem::path& a, const std::filesystem::path& b) {
  const Bundle x = ReadBundle(a), y = ReadBundle(b);
  ASSERT_EQ(x.light_field.size(), y.light_field.size());
  EXPECT_EQ(0, std::memcmp(x.light_field.data(), y.light_field.data(), x.light_field.size() * sizeof(float)));
  ASSERT_TRUE(x.disparity && y.disparity && x.labels && y.labels);
  EXPECT_EQ(0, std::memcmp(x.disparity->data(), y.disparity->data(),
                           static_cast<std::size_t>(x.disparity->width() * x.disparity->height()) * sizeof(float)));
  EXPECT_EQ(0, std::memcmp(x.labels->data(), y.labels->data(), x.labels->size() * sizeof(std::int32_t)));
}

TEST(SimulateCli, SameSeedGivesIdenticalFiles) {
  testing::TempDir dir;
  const std::vector<std::string> args = {"simulate", "--camera", "mini-illum",   "--scene", "two-horses",
                                         "--seed",   "7",        "--hot-pixels", "4"};
  auto with_out = [&](const std::string& out) {
    auto a = args;
    a.push_back("--out");
    a.push_back(out);
    return a;
  };
  const auto r1 = testing::RunLfsp(with_out((dir / "a").string()));
  ASSERT_EQ(r1.exit_status, 0) << r1.err;
  const auto r2 = testing::RunLfsp(with_out((dir / "b").string()));
  ASSERT_EQ(r2.exit_status, 0) << r2.err;
  const auto files = FilesUnder(dir / "a");
  ASSERT_EQ(files, FilesUnder(dir / "b"));
  int compared = 0;
  for (const auto& file : files) {
    if (file == "summary.json") continue;  // holds timings
    if (file.extension() == ".h5") {
      // HDF5 object headers carry modification times (core's writer does not disable them): compare contents.
      ExpectSameBundle(dir / "a" / file, dir / "b" / file);
      continue;
    }
    EXPECT_EQ(testing::ReadBytes(dir / "a" / file), testing::ReadBytes(dir / "b" / file)) << file;
    ++compared;
  }
  EXPECT_GE(compared, 14);  // capture, 6 white RAW + 6 TXT, geometry, scene
  // A different seed changes the capture (noise, hot pixels) but not the lattice.
  auto other = with_out((dir / "c").string());
  other[6] = "8";
  other.push_back("--no-white-images");
  ASSERT_EQ(testing::RunLfsp(other).exit_status, 0);
  EXPECT_NE(testing::ReadBytes(dir / "a" / "capture.LFR"), testing::ReadBytes(dir / "c" / "capture.LFR"));
  auto lattice = [](const std::filesystem::path& path) {
    return nlohmann::json::parse(testing::ReadBytes(path))["lattice"];
  };
  EXPECT_EQ(lattice(dir / "a" / "ground_truth" / "lenslet_geometry.json"),
            lattice(dir / "c" / "ground_truth" / "lenslet_geometry.json"));
}

TEST(SimulateCli, IdealOnlyWritesALoadableBundleWithGroundTruth) {
  testing::TempDir dir;
  const auto r = testing::RunLfsp({"simulate", "--ideal-only", "--scene", "spheres", "--views", "5", "--size", "48x40",
                                   "--out", (dir / "ideal").string()});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const Bundle bundle = LoadLightField(dir / "ideal" / "ideal.h5");
  EXPECT_EQ(bundle.light_field.shape(), (LightFieldShape{5, 5, 48, 40, 3}));
  ASSERT_TRUE(bundle.disparity.has_value());
  ASSERT_TRUE(bundle.labels.has_value());
  EXPECT_TRUE(std::filesystem::exists(dir / "ideal" / "summary.json"));
}

TEST(SimulateCli, BadInputExitsWithStatus2AndAMessage) {
  testing::TempDir dir;
  auto r = testing::RunLfsp({"simulate", "--scene", (dir / "missing.json").string(), "--out", (dir / "o").string()});
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_NE(r.err.find("missing.json"), std::string::npos) << r.err;
  testing::WriteBytes(dir / "bad.json", R"({"objects": [{"texture": {"type": "checker", "period": -1}}]})");
  r = testing::RunLfsp({"simulate", "--scene", (dir / "bad.json").string(), "--out", (dir / "o").string()});
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_NE(r.err.find("period"), std::string::npos) << r.err;
  r = testing::RunLfsp({"simulate", "--ideal-only", "--size", "12by12", "--out", (dir / "o").string()});
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
}

// A scene's image texture that is cut short is refused with lfsp's one line and nothing written: libpng printed a
// line of its own first when textures were read with cv::imread.
TEST(SimulateCli, TruncatedImageTextureGivesOneLine) {
  testing::TempDir dir;
  cv::Mat texture(32, 32, CV_8UC3);
  cv::randu(texture, 0, 256);
  ASSERT_TRUE(cv::imwrite((dir / "texture.png").string(), texture));
  const std::string bytes = testing::ReadBytes(dir / "texture.png");
  testing::WriteBytes(dir / "texture.png", bytes.substr(0, bytes.size() / 2));
  testing::WriteBytes(dir / "scene.json",
                      R"({"objects": [{"disparity": 0.5, "texture": {"type": "image", "path": "texture.png"}}]})");
  const auto r = testing::RunLfsp({"simulate", "--ideal-only", "--views", "3", "--size", "32x32", "--scene",
                                   (dir / "scene.json").string(), "--out", (dir / "o").string()});
  EXPECT_EQ(r.exit_status, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("lfsp: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find((dir / "texture.png").string()), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "o"));

  // A texture declaring far more pixels than its bytes hold (scene_test.cc builds one) is refused before any
  // allocation: one line, and the run stays small.
  testing::WriteBytes(dir / "texture.png", testing::PngDeclaring(100000, 100000));
  const auto huge = testing::RunLfsp({"simulate", "--ideal-only", "--views", "3", "--size", "32x32", "--scene",
                                      (dir / "scene.json").string(), "--out", (dir / "o").string()});
  EXPECT_EQ(huge.exit_status, 2) << huge.err;
  EXPECT_EQ(std::count(huge.err.begin(), huge.err.end(), '\n'), 1) << huge.err;
  EXPECT_NE(huge.err.find("declares"), std::string::npos) << huge.err;
  EXPECT_LT(huge.peak_rss_kb, 1024L * 1024L) << huge.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "o"));
}

// The bundled samples load, and their geometry matches the camera model in this build (regenerate them with
// tools/make_samples when the model changes).
TEST(Samples, BundledSamplesLoadAndMatchTheModel) {
  const auto samples = testing::SourceDir() / "samples";
  const Bundle ideal = LoadLightField(samples / "ideal" / "ideal.h5");
  EXPECT_EQ(ideal.light_field.shape().nu, 7);
  EXPECT_TRUE(ideal.disparity.has_value() && ideal.labels.has_value());
  for (const auto& [folder, camera_name, file] :
       {std::tuple{"mini-illum", "mini-illum", "capture.LFR"}, {"mini-f01", "mini-f01", "capture.lfp"}}) {
    SCOPED_TRACE(folder);
    const auto root = samples / folder;
    const decode::LytroCapture capture = decode::OpenLytroCapture(root / file);
    const CameraModel camera = CameraPreset(camera_name);
    EXPECT_EQ(capture.ReadRawImage().width, camera.sensor_width);
    std::ifstream in(root / "ground_truth" / "lenslet_geometry.json");
    const auto geometry = nlohmann::json::parse(in);
    const LensletLattice lattice =
        MakeLattice(camera, camera.white_settings[static_cast<std::size_t>(camera.capture_setting)]);
    EXPECT_NEAR(geometry["lattice"]["spacing_px"].get<double>(), lattice.spacing, 1e-9);
    EXPECT_NEAR(geometry["lattice"]["origin_px"][0].get<double>(), lattice.origin_x, 1e-9);
    EXPECT_EQ(geometry["lattice"]["columns"].get<int>(), lattice.columns);
    const Bundle gt = ReadBundle(root / "ground_truth" / "decoded.h5");
    EXPECT_EQ(gt.light_field.shape().width, MakeDecodedGrid(camera, lattice).width);
    EXPECT_TRUE(gt.light_field.HasWeights());
    for (std::size_t k = 0; k < camera.white_settings.size(); ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "MOD_%04zu.RAW", k);
      EXPECT_TRUE(decode::OpenLytroCapture(root / "whites" / name).IsWhiteImage()) << name;
    }
  }
}

}  // namespace
}  // namespace lfsp::simulate
