// Peak memory bounded by design (issue 46, item 4): `lfsp decode` and `lfsp pipeline` on a full-size simulated Illum
// capture stay under bounds computed from the capture's size, as docs/DESIGN.md ("Peak memory") derives them. With
// P sensor pixels and R decoded rays (15x15 views):
//
//   decode:   18 B x P + 16 B x R + 250 MB   (the slicing step: the white image's grey version, lens labels and
//                                             demosaicked RGB per pixel; the light field, RGB + weight, per ray;
//                                             the capture and the white image's inverse are freed before it, as
//                                             this capture has no clipped sample)
//   pipeline: the decode's, plus one row of views of a simulated capture's truth (16 B per ray of the row): the
//             pipeline compares the decode with its ideal light field a row of views at a time, and reads the
//             truth's labels only for the views it keeps, once the others are gone
//
// The peak is the command's max RSS (wait4's ru_maxrss, measured by RunLfsp). Before issue 46 the decode peaked at
// 2632 MB and the pipeline at 2672 MB on this capture, over both bounds (2272 and 2334 MB). The pipeline read the
// whole truth beside the decoded light field until the thirty-second session: 2275 MB, 1.15 GB of it the truth's
// samples, weights and labels (now 1986 MB, as the decode). Since that is within the design bound, the pipeline's
// peak is also held to the decode's measured one plus the truth's row (2048 MB), which main's 2275 MB failed.
// The thirty-third session freed the capture and the white image's inverse before the demosaic and made the
// demosaic's mask by bands: the decode went from 2096 to 1744 MB, and the bound from 24 B x P + 400 MB (2272 MB)
// to 18 B x P + 250 MB (1885 MB), which 1269048's decode fails.
// There is no timing assert: the test passes on a busy machine, only slowly.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using lfsp::testing::ReadBytes;
using lfsp::testing::RunLfsp;
using lfsp::testing::TempDir;

// Bytes per sensor pixel held at the decode's peak: the white image's grey floats (4), the lens labels (1), the
// demosaicked RGB floats (12), and 1 for transient buffers.
constexpr double kSensorBytes = 18.0;
// Bytes per decoded ray: RGB floats and a weight.
constexpr double kRayBytes = 16.0;
// Code, libraries, thread stacks, small tables and the allocator's slack (MB of 2^20 bytes, as ru_maxrss / 1024).
constexpr double kFixedMegabytes = 250.0;
constexpr double kMegabyte = 1048576.0;

struct Sizes {
  double sensor_pixels = 0.0;
  double rays = 0.0;
  double view_rows = 1.0;
};

Sizes SizesFrom(const nlohmann::json& decode_summary) {
  const nlohmann::json& grid = decode_summary["grid"];
  const nlohmann::json& field = decode_summary["light_field"];
  return {grid["sensor_width"].get<double>() * grid["sensor_height"].get<double>(),
          field["nu"].get<double>() * field["nv"].get<double>() * field["width"].get<double>() *
              field["height"].get<double>(),
          field["nv"].get<double>()};
}

double DecodeBound(const Sizes& sizes) {
  return (kSensorBytes * sizes.sensor_pixels + kRayBytes * sizes.rays) / kMegabyte + kFixedMegabytes;
}

// One row of views of the simulated capture's truth: RGB floats and a weight per ray.
double TruthRowMegabytes(const Sizes& sizes) { return kRayBytes * sizes.rays / sizes.view_rows / kMegabyte; }

double PipelineBound(const Sizes& sizes) { return DecodeBound(sizes) + TruthRowMegabytes(sizes); }

TEST(MemoryBound, FullSizeIllumCaptureDecodeAndPipelineStayUnderTheDesignBound) {
  TempDir temp;
  const fs::path simulated = temp / "sim";
  const auto simulate =
      RunLfsp({"-q", "simulate", "--camera", "illum", "--scene", "two-horses", "--out", simulated.string()});
  ASSERT_EQ(simulate.exit_status, 0) << simulate.err;
  const fs::path capture = simulated / "capture.LFR";

  const auto decode = RunLfsp({"-q", "decode", capture.string(), "--out", (temp / "decoded.h5").string()});
  ASSERT_EQ(decode.exit_status, 0) << decode.err;
  const nlohmann::json summary = nlohmann::json::parse(ReadBytes(temp / "decoded.summary.json"));
  const Sizes sizes = SizesFrom(summary);
  ASSERT_EQ(sizes.sensor_pixels, 7728.0 * 5368.0);
  const double decode_peak = static_cast<double>(decode.peak_rss_kb) / 1024.0;
  std::printf("sensor %.1f Mpixel, %.1f M rays: decode peak %.0f MB, bound %.0f MB\n", sizes.sensor_pixels * 1e-6,
              sizes.rays * 1e-6, decode_peak, DecodeBound(sizes));
  EXPECT_LE(decode_peak, DecodeBound(sizes));
  // The decode reports its own memory step by step: the same peak, seen from inside.
  ASSERT_TRUE(summary["decode"].contains("peak_resident_mb"));
  EXPECT_LE(summary["decode"]["peak_resident_mb"]["slice"].get<double>(), decode_peak + 1.0);

  const auto pipeline = RunLfsp({"-q", "pipeline", capture.string(), "--out", (temp / "run").string()});
  ASSERT_EQ(pipeline.exit_status, 0) << pipeline.err;
  const double pipeline_peak = static_cast<double>(pipeline.peak_rss_kb) / 1024.0;
  std::printf("pipeline peak %.0f MB, bound %.0f MB, decode peak + a row of the truth %.0f MB\n", pipeline_peak,
              PipelineBound(sizes), decode_peak + TruthRowMegabytes(sizes));
  EXPECT_LE(pipeline_peak, PipelineBound(sizes));
  // The same bound against the decode as measured: the pipeline's decode writes no file, so the truth's one row is
  // all it may add (the whole truth added 1.2 GB).
  EXPECT_LE(pipeline_peak, decode_peak + TruthRowMegabytes(sizes));
  const nlohmann::json run = nlohmann::json::parse(ReadBytes(temp / "run" / "summary.json"));
  ASSERT_TRUE(run.contains("memory"));
  for (const auto& [stage, memory] : run["memory"].items())
    EXPECT_LE(memory["peak_resident_mb"].get<double>(), pipeline_peak + 1.0) << stage;
}

}  // namespace
}  // namespace lfsp
