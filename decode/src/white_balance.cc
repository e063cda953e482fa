#include "lfsp/decode/white_balance.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "lfsp/core/error.h"
#include "lfsp/core/ordered_reduction.h"

namespace lfsp::decode {
namespace {

// A pixel is grey when, after the gains and the colour matrix, its largest channel is at most this many times its
// smallest (about 13 % saturation).
constexpr double kGreyRatio = 1.3;
// Below this share of the usable pixels the grey ones are too few to trust: the start gains stay.
constexpr double kMinGreyFraction = 0.002;
constexpr int kMaxRounds = 100;
// How far the estimate may move from the start gains, per channel: daylight to tungsten is about 2x in R/B.
constexpr double kMaxCorrection = 2.5;

std::string Join(const std::array<double, 3>& gains) {
  std::ostringstream text;
  text << gains[0] << "," << gains[1] << "," << gains[2];
  return text.str();
}

// Sums of the sensor RGB of the grey pixels under `gains`, and how many pixels were usable and grey.
struct GreySums {
  std::array<double, 3> sum = {0.0, 0.0, 0.0};
  long long grey = 0;
  long long usable = 0;
};

GreySums SumGreyPixels(const cv::Mat& rgb, const cv::Mat& grey_white, const std::array<double, 9>& ccm,
                       const std::array<double, 3>& gains, float clip_level) {
  constexpr int kStride = 2;  // every other row and column: the estimate is a mean over millions of pixels
  const int rows = (rgb.rows + kStride - 1) / kStride;
  // Summed in a fixed order (OrderedParallelSum), so that the gains, and the decode, do not depend on the threads.
  return OrderedParallelSum(
      rows, [] { return GreySums{}; },
      [&](int item, GreySums& sums) {
        const int y = item * kStride;
        const float* p = rgb.ptr<float>(y);
        const float* w = grey_white.ptr<float>(y);
        for (int x = 0; x < rgb.cols; x += kStride) {
          if (w[x] < 0.5f) continue;
          const float* in = p + 3 * x;
          if (std::max({in[0], in[1], in[2]}) >= clip_level || std::min({in[0], in[1], in[2]}) <= 0.0f) continue;
          ++sums.usable;
          const double br = gains[0] * in[0], bg = gains[1] * in[1], bb = gains[2] * in[2];
          const double out_r = ccm[0] * br + ccm[1] * bg + ccm[2] * bb;
          const double out_g = ccm[3] * br + ccm[4] * bg + ccm[5] * bb;
          const double out_b = ccm[6] * br + ccm[7] * bg + ccm[8] * bb;
          const double low = std::min({out_r, out_g, out_b}), high = std::max({out_r, out_g, out_b});
          if (!(low > 0.0) || high > kGreyRatio * low) continue;
          for (int c = 0; c < 3; ++c) sums.sum[static_cast<std::size_t>(c)] += in[c];
          ++sums.grey;
        }
      },
      [](GreySums& into, const GreySums& from) {
        for (int c = 0; c < 3; ++c) into.sum[static_cast<std::size_t>(c)] += from.sum[static_cast<std::size_t>(c)];
        into.grey += from.grey;
        into.usable += from.usable;
      });
}

// The level above which a channel counts as clipped: just under the brightest well-lit sample.
float ClipLevel(const cv::Mat& rgb, const cv::Mat& grey_white) {
  float brightest = 0.0f;
#pragma omp parallel for schedule(static) reduction(max : brightest)
  for (int y = 0; y < rgb.rows; y += 2) {
    const float* p = rgb.ptr<float>(y);
    const float* w = grey_white.ptr<float>(y);
    for (int x = 0; x < rgb.cols; x += 2)
      if (w[x] >= 0.5f) brightest = std::max({brightest, p[3 * x], p[3 * x + 1], p[3 * x + 2]});
  }
  return 0.95f * brightest;
}

}  // namespace

WhiteBalance WhiteBalanceFromString(const std::string& text) {
  if (text == "camera") return {WhiteBalanceMode::kCamera, {1, 1, 1}};
  if (text == "auto") return {WhiteBalanceMode::kAuto, {1, 1, 1}};
  if (text == "none") return {WhiteBalanceMode::kNone, {1, 1, 1}};
  WhiteBalance balance{WhiteBalanceMode::kGains, {0, 0, 0}};
  std::istringstream fields(text);
  char comma1 = 0, comma2 = 0;
  fields >> balance.gains[0] >> comma1 >> balance.gains[1] >> comma2 >> balance.gains[2];
  const bool positive = std::all_of(balance.gains.begin(), balance.gains.end(),
                                    [](double g) { return std::isfinite(g) && g > 0.0 && g < 1e3; });
  if (!fields || comma1 != ',' || comma2 != ',' || !fields.eof() || !positive)
    throw Error(OptionName("white_balance") + " '" + text +
                "': expected auto, camera, none or three positive gains R,G,B (e.g. 1.9,1,1.4)");
  const double green = balance.gains[1];
  for (double& g : balance.gains) g /= green;
  return balance;
}

std::string ToString(const WhiteBalance& balance) {
  switch (balance.mode) {
    case WhiteBalanceMode::kCamera:
      return "camera";
    case WhiteBalanceMode::kAuto:
      return "auto";
    case WhiteBalanceMode::kNone:
      return "none";
    case WhiteBalanceMode::kGains:
      break;
  }
  return Join(balance.gains);
}

std::array<double, 3> CameraWhiteBalanceGains(const LytroMetadata& metadata) {
  const auto& gain = metadata.colour.white_balance_gain;
  if (!gain || !(gain->gr > 0) || !(gain->gb > 0)) return {1.0, 1.0, 1.0};
  const double green = 0.5 * (gain->gr + gain->gb);
  return {gain->r / green, 1.0, gain->b / green};
}

nlohmann::json AutoWhiteBalanceReport::ToJson() const {
  return {{"start_gains", start},
          {"gains", gains},
          {"grey_fraction", grey_fraction},
          {"rounds", rounds},
          {"kept_start", kept_start}};
}

std::array<double, 3> EstimateWhiteBalance(const cv::Mat& rgb, const cv::Mat& grey_white,
                                           const std::array<double, 9>& ccm, const std::array<double, 3>& start,
                                           AutoWhiteBalanceReport* report) {
  AutoWhiteBalanceReport local;
  AutoWhiteBalanceReport& out = report ? *report : local;
  out = {};
  out.start = start;
  const float clip_level = ClipLevel(rgb, grey_white);
  std::array<double, 3> gains = start;
  for (out.rounds = 1; out.rounds <= kMaxRounds; ++out.rounds) {
    const GreySums sums = SumGreyPixels(rgb, grey_white, ccm, gains, clip_level);
    out.grey_fraction = sums.usable > 0 ? static_cast<double>(sums.grey) / static_cast<double>(sums.usable) : 0.0;
    if (out.grey_fraction < kMinGreyFraction || !(sums.sum[0] > 0) || !(sums.sum[2] > 0)) {
      out.kept_start = true;
      gains = start;
      break;
    }
    std::array<double, 3> next = {sums.sum[1] / sums.sum[0], 1.0, sums.sum[1] / sums.sum[2]};
    for (int c : {0, 2})
      next[static_cast<std::size_t>(c)] =
          std::clamp(next[static_cast<std::size_t>(c)], start[static_cast<std::size_t>(c)] / kMaxCorrection,
                     start[static_cast<std::size_t>(c)] * kMaxCorrection);
    const double change = std::max(std::abs(std::log(next[0] / gains[0])), std::abs(std::log(next[2] / gains[2])));
    gains = next;
    if (change < 0.002) break;
  }
  out.rounds = std::min(out.rounds, kMaxRounds);
  out.gains = gains;
  return gains;
}

}  // namespace lfsp::decode
