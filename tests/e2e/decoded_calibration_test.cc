// Issue 12's calibration criterion through the CLI as a user runs it: `lfsp simulate --calibration 8 --camera f01`
// writes full-size F01 captures of a checkerboard at eight known poses, each is decoded with its white images, and
// `lfsp calibrate --corners 7x5 --square-size 25` fits them. The RMS ray reprojection error and every pose's distance
// to its first inner corner are checked against the simulator's ground truth (ground_truth.json of each pose).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using lfsp::testing::LoadJson;
using lfsp::testing::RunLfsp;
using lfsp::testing::TempDir;

// Where `lfsp simulate --calibration` puts pose k: calibration/pose_NN.
fs::path PoseFolder(const fs::path& simulated, int k) {
  char name[16];
  std::snprintf(name, sizeof name, "pose_%02d", k);
  return simulated / "calibration" / name;
}

double Norm(const nlohmann::json& v) {
  return std::sqrt(v[0].get<double>() * v[0].get<double>() + v[1].get<double>() * v[1].get<double>() +
                   v[2].get<double>() * v[2].get<double>());
}

TEST(DecodedCalibration, F01CheckerboardCapturesGiveTheTruePoses) {
  constexpr int kPoses = 8;
  TempDir temp;
  const fs::path simulated = temp / "sim";
  const auto simulate = RunLfsp(
      {"-q", "simulate", "--calibration", std::to_string(kPoses), "--camera", "f01", "--out", simulated.string()});
  ASSERT_EQ(simulate.exit_status, 0) << simulate.err;
  std::vector<std::string> calibrate{"-q", "calibrate"};
  for (int k = 0; k < kPoses; ++k) {
    const fs::path pose = PoseFolder(simulated, k);
    const fs::path decoded = temp / ("pose_" + std::to_string(k) + ".h5");
    const auto decode = RunLfsp({"-q", "decode", (pose / "capture.lfp").string(), "--white-images",
                                 (simulated / "whites").string(), "--out", decoded.string()});
    ASSERT_EQ(decode.exit_status, 0) << decode.err;
    calibrate.push_back(decoded.string());
  }
  const fs::path result = temp / "cal.json";
  for (const char* argument : {"--corners", "7x5", "--square-size", "25", "--out"}) calibrate.push_back(argument);
  calibrate.push_back(result.string());
  const auto run = RunLfsp(calibrate);
  ASSERT_EQ(run.exit_status, 0) << run.err;

  const nlohmann::json calibration = LoadJson(result);
  const double rms_mm = calibration.at("rms_mm").get<double>();
  ASSERT_EQ(calibration.at("captures").size(), static_cast<std::size_t>(kPoses));
  double worst_distance = 0;
  for (int k = 0; k < kPoses; ++k) {
    // The calibration's board origin is the first inner corner in its canonical order, the truth's corner 0.
    const nlohmann::json truth = LoadJson(PoseFolder(simulated, k) / "ground_truth.json");
    const double estimated = Norm(calibration.at("captures")[static_cast<std::size_t>(k)].at("translation_m"));
    const double true_distance = Norm(truth.at("corners")[0].at("camera_m"));
    worst_distance = std::max(worst_distance, std::abs(estimated / true_distance - 1.0));
  }
  std::printf("decoded F01 checkerboards: RMS %.4f mm; worst pose distance off by %.3f %%\n", rms_mm,
              100.0 * worst_distance);
  // Issue 12 asks for 0.05 mm and 1 %. Measured 0.0345 mm and 0.040 %. It was 0.228 mm before the simulator spread
  // each lens's rays over its aperture and corners went to the blurred view's saddle point, and 0.0514 mm before
  // the views at the lenslet's edge were left out.
  EXPECT_LT(rms_mm, 0.04);
  EXPECT_LT(worst_distance, 0.01);
  // The automatic view border skipped the rim of each micro-lens image: the 9x9 decode's outer ring, at least.
  for (const auto& capture : calibration.at("captures")) EXPECT_GE(capture.at("edge_views").size(), 20u);
}

}  // namespace
}  // namespace lfsp
