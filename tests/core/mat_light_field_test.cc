// MATLAB .mat light fields (issue 17, item 2): fixtures written by hand in both layouts (LFToolbox's v5 uint16
// LF(v,u,y,x,c) with its weight channel, the deep-learning [U,V,H,W,3] as v7.3 HDF5 the way h5py shows it), read
// back sample by sample, and our own LFToolbox-layout writer round-tripped.

#include <H5Cpp.h>
#include <gtest/gtest.h>
#include <matio.h>

#include <cstdint>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/load.h"
#include "lfsp/core/mat_light_field.h"
#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using testing::RunLfsp;
using testing::TempDir;

constexpr int kNv = 3, kNu = 4, kH = 5, kW = 6;

// A value that says where it came from: each index moves it by a different amount.
double Coded(int v, int u, int y, int x, int c) { return (v * 1000 + u * 100 + y * 10 + x + c * 0.5) / 4000.0; }

std::size_t MatlabIndex(int v, int u, int y, int x, int c) {
  return static_cast<std::size_t>(v + kNv * (u + kNu * (y + kH * (x + kW * c))));
}

TEST(MatLightField, LfToolboxV5WithWeights) {
  TempDir temp;
  const fs::path path = temp / "lftoolbox.mat";
  std::vector<std::uint16_t> data(static_cast<std::size_t>(kNv * kNu * kH * kW * 4));
  for (int v = 0; v < kNv; ++v)
    for (int u = 0; u < kNu; ++u)
      for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
          for (int c = 0; c < 4; ++c)
            data[MatlabIndex(v, u, y, x, c)] = static_cast<std::uint16_t>(std::lround(Coded(v, u, y, x, c) * 65535));
  {
    mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5);
    ASSERT_NE(mat, nullptr);
    std::size_t dims[5] = {kNv, kNu, kH, kW, 4};
    matvar_t* var = Mat_VarCreate("LF", MAT_C_UINT16, MAT_T_UINT16, 5, dims, data.data(), MAT_F_DONT_COPY_DATA);
    ASSERT_EQ(Mat_VarWrite(mat, var, MAT_COMPRESSION_ZLIB), 0);
    Mat_VarFree(var);
    Mat_Close(mat);
  }
  const LightField lf = LoadLightField(path).light_field;
  ASSERT_EQ(lf.shape().nv, kNv);
  ASSERT_EQ(lf.shape().nu, kNu);
  ASSERT_EQ(lf.shape().height, kH);
  ASSERT_EQ(lf.shape().width, kW);
  ASSERT_TRUE(lf.HasWeights());
  for (const auto& [v, u, y, x] : {std::array{0, 0, 0, 0}, std::array{2, 3, 4, 5}, std::array{1, 2, 3, 1}}) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(lf.at({u, v}, y, x, c), Coded(v, u, y, x, c), 1e-4);
    EXPECT_NEAR(lf.weights().at({u, v}, y, x, 0), Coded(v, u, y, x, 3), 1e-4);
  }
}

TEST(MatLightField, DeepLearningV73AsH5pyShowsIt) {
  TempDir temp;
  const fs::path path = temp / "basiclfsr.mat";
  {
    // MATLAB's LF [U,V,H,W,3] (column-major) is HDF5 (3, W, H, V, U) in C order.
    H5::H5File file(path.string(), H5F_ACC_TRUNC);
    const hsize_t dims[5] = {3, kW, kH, kNu, kNv};
    std::vector<double> data(static_cast<std::size_t>(3 * kW * kH * kNu * kNv));
    for (int v = 0; v < kNv; ++v)
      for (int u = 0; u < kNu; ++u)
        for (int y = 0; y < kH; ++y)
          for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c) data[MatlabIndex(v, u, y, x, c)] = Coded(v, u, y, x, c);
    H5::DataSet dataset = file.createDataSet("LF", H5::PredType::NATIVE_DOUBLE, H5::DataSpace(5, dims));
    dataset.write(data.data(), H5::PredType::NATIVE_DOUBLE);
  }
  const LightField lf = ReadMatLightField(path);
  EXPECT_EQ(lf.shape().nv, kNv);
  EXPECT_EQ(lf.shape().nu, kNu);
  EXPECT_FALSE(lf.HasWeights());
  EXPECT_NEAR(lf.at({3, 2}, 4, 5, 2), Coded(2, 3, 4, 5, 2), 1e-6);
  EXPECT_NEAR(lf.at({1, 0}, 2, 3, 0), Coded(0, 1, 2, 3, 0), 1e-6);
}

TEST(MatLightField, WrittenInLfToolboxLayoutAndReadBack) {
  TempDir temp;
  LightField lf({kNu, kNv, kW, kH, 3});
  lf.EnableWeights();
  for (int v = 0; v < kNv; ++v)
    for (int u = 0; u < kNu; ++u)
      for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
          for (int c = 0; c < 3; ++c) lf.at({u, v}, y, x, c) = static_cast<float>(Coded(v, u, y, x, c));
          lf.weights().at({u, v}, y, x, 0) = static_cast<float>(Coded(v, u, y, x, 3));
        }
  Bundle bundle;
  bundle.light_field = lf;
  SaveLightField(bundle, temp / "out.mat");
  const LightField back = ReadMatLightField(temp / "out.mat");
  ASSERT_EQ(back.shape().nu, kNu);
  ASSERT_TRUE(back.HasWeights());
  for (std::size_t i = 0; i < lf.size(); ++i) EXPECT_NEAR(back.data()[i], lf.data()[i], 1.0 / 65535);
  for (std::size_t i = 0; i < lf.weights().size(); ++i)
    EXPECT_NEAR(back.weights().data()[i], lf.weights().data()[i], 1.0 / 65535);
  // The CLI describes it, and bad .mat files are one-line errors.
  const auto info = RunLfsp({"info", (temp / "out.mat").string()});
  EXPECT_EQ(info.exit_status, 0) << info.err;
  EXPECT_NE(info.out.find("4 x 3"), std::string::npos) << info.out;
  testing::WriteBytes(temp / "junk.mat", "MATLAB 5.0 MAT-file, garbage");
  const auto junk = RunLfsp({"info", (temp / "junk.mat").string()});
  EXPECT_EQ(junk.exit_status, 2);
  EXPECT_EQ(std::count(junk.err.begin(), junk.err.end(), '\n'), 1) << junk.err;
  const std::string bytes = testing::ReadBytes(temp / "out.mat");
  testing::WriteBytes(temp / "short.mat", bytes.substr(0, bytes.size() / 2));
  const auto cut = RunLfsp({"info", (temp / "short.mat").string()});
  EXPECT_EQ(cut.exit_status, 2) << cut.err;
  EXPECT_EQ(std::count(cut.err.begin(), cut.err.end(), '\n'), 1) << cut.err;
}

}  // namespace
}  // namespace lfsp
