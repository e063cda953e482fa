#include "lfsp/decode/white_balance.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "bayer_levels.h"
#include "lfsp/core/error.h"
#include "lfsp/core/ordered_reduction.h"

namespace lfsp::decode {
namespace {

// A pixel is grey when, after the gains and the colour matrix, its largest channel is at most this many times its
// smallest (about 13 % saturation).
constexpr double kGreyRatio = 1.3;
// The tolerances tried in turn, from the start gains, while the first round at one finds too few grey pixels: a light
// far from the one the start gains were made for can leave no surface within kGreyRatio of neutral. The real F01
// frames' shade is bluer than the camera's reference, and under its gains IMG_3's leaves and dark ground are all green
// or cyan: 0.12 % of its pixels are within 1.3x, below kMinGreyFraction. A looser tolerance finds the least coloured
// surfaces; from where it settles, the search goes on at kGreyRatio.
constexpr double kGreyRatios[] = {kGreyRatio, 1.6, 2.0};
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

// The pixels every round weighs: on every other row and column (the estimate is a mean over millions of pixels),
// lit by the white image, unclipped, no channel at or below zero. They do not depend on the gains, so they are
// gathered once, row by row in the order the rounds add them, and the rounds (15-17 on the real F01 frames) read a
// packed copy instead of two sensor-size images each: those reads, not the arithmetic, were the step's time.
struct UsablePixels {
  std::vector<float> rgb;              // three per pixel
  std::vector<std::size_t> row_start;  // pixel index where each sampled row starts, and one past the last
};

UsablePixels GatherUsablePixels(const cv::Mat& rgb, const cv::Mat& grey_white, float clip_level) {
  constexpr int kStride = 2;
  const int rows = (rgb.rows + kStride - 1) / kStride;
  // Written as the tests that skip a pixel, negated, so that a NaN decides as it always did.
  const auto usable = [&](const float* in, float white) {
    return !(white < 0.5f) && !(std::max({in[0], in[1], in[2]}) >= clip_level) &&
           !(std::min({in[0], in[1], in[2]}) <= 0.0f);
  };
  UsablePixels pixels;
  pixels.row_start.assign(static_cast<std::size_t>(rows) + 1, 0);
#pragma omp parallel for schedule(static)
  for (int item = 0; item < rows; ++item) {
    const float* p = rgb.ptr<float>(item * kStride);
    const float* w = grey_white.ptr<float>(item * kStride);
    std::size_t count = 0;
    for (int x = 0; x < rgb.cols; x += kStride) count += usable(p + 3 * x, w[x]) ? 1 : 0;
    pixels.row_start[static_cast<std::size_t>(item) + 1] = count;
  }
  for (std::size_t i = 1; i < pixels.row_start.size(); ++i) pixels.row_start[i] += pixels.row_start[i - 1];
  pixels.rgb.resize(3 * pixels.row_start.back());
#pragma omp parallel for schedule(static)
  for (int item = 0; item < rows; ++item) {
    const float* p = rgb.ptr<float>(item * kStride);
    const float* w = grey_white.ptr<float>(item * kStride);
    float* out = pixels.rgb.data() + 3 * pixels.row_start[static_cast<std::size_t>(item)];
    for (int x = 0; x < rgb.cols; x += kStride) {
      const float* in = p + 3 * x;
      if (!usable(in, w[x])) continue;
      out[0] = in[0];
      out[1] = in[1];
      out[2] = in[2];
      out += 3;
    }
  }
  return pixels;
}

GreySums SumGreyPixels(const UsablePixels& pixels, const std::array<double, 9>& ccm, const std::array<double, 3>& gains,
                       double grey_ratio) {
  const int rows = static_cast<int>(pixels.row_start.size()) - 1;
  // Summed in a fixed order (OrderedParallelSum), so that the gains, and the decode, do not depend on the threads.
  return OrderedParallelSum(
      rows, [] { return GreySums{}; },
      [&](int item, GreySums& sums) {
        const std::size_t begin = pixels.row_start[static_cast<std::size_t>(item)];
        const std::size_t end = pixels.row_start[static_cast<std::size_t>(item) + 1];
        for (std::size_t i = begin; i < end; ++i) {
          const float* in = pixels.rgb.data() + 3 * i;
          ++sums.usable;
          const double br = gains[0] * in[0], bg = gains[1] * in[1], bb = gains[2] * in[2];
          const double out_r = ccm[0] * br + ccm[1] * bg + ccm[2] * bb;
          const double out_g = ccm[3] * br + ccm[4] * bg + ccm[5] * bb;
          const double out_b = ccm[6] * br + ccm[7] * bg + ccm[8] * bb;
          const double low = std::min({out_r, out_g, out_b}), high = std::max({out_r, out_g, out_b});
          if (!(low > 0.0) || high > grey_ratio * low) continue;
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

// Rounds at one grey tolerance, starting from `gains`: the grey pixels' mean is made grey until the gains settle (a
// change below 0.2 %), each gain kept within kMaxCorrection of `start`. Nothing when a round finds too few grey
// pixels. Counts its rounds into `report.rounds` and leaves the last round's grey share in `report.grey_fraction`.
std::optional<std::array<double, 3>> SettleOnGrey(const UsablePixels& usable, const std::array<double, 9>& ccm,
                                                  const std::array<double, 3>& start, std::array<double, 3> gains,
                                                  double grey_ratio, AutoWhiteBalanceReport& report) {
  for (int round = 0; round < kMaxRounds; ++round) {
    ++report.rounds;
    const GreySums sums = SumGreyPixels(usable, ccm, gains, grey_ratio);
    report.grey_fraction = sums.usable > 0 ? static_cast<double>(sums.grey) / static_cast<double>(sums.usable) : 0.0;
    if (report.grey_fraction < kMinGreyFraction || !(sums.sum[0] > 0) || !(sums.sum[2] > 0)) return std::nullopt;
    std::array<double, 3> next = {sums.sum[1] / sums.sum[0], 1.0, sums.sum[1] / sums.sum[2]};
    for (int c : {0, 2})
      next[static_cast<std::size_t>(c)] =
          std::clamp(next[static_cast<std::size_t>(c)], start[static_cast<std::size_t>(c)] / kMaxCorrection,
                     start[static_cast<std::size_t>(c)] * kMaxCorrection);
    const double change = std::max(std::abs(std::log(next[0] / gains[0])), std::abs(std::log(next[2] / gains[2])));
    gains = next;
    if (change < 0.002) break;
  }
  return gains;
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

std::array<double, 9> CameraColourMatrix(const LytroMetadata& metadata) {
  return metadata.colour.ccm.value_or(std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1});
}

nlohmann::json AutoWhiteBalanceReport::ToJson() const {
  return {{"start_gains", start},
          {"gains", gains},
          {"start_grey_ratio", start_grey_ratio},
          {"settled_grey_ratio", settled_grey_ratio},
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
  out.gains = start;
  out.kept_start = true;
  const UsablePixels usable = GatherUsablePixels(rgb, grey_white, ClipLevel(rgb, grey_white));
  std::optional<std::array<double, 3>> settled;
  for (const double ratio : kGreyRatios) {
    out.start_grey_ratio = ratio;
    const int rounds_before = out.rounds;
    settled = SettleOnGrey(usable, ccm, start, start, ratio, out);
    if (settled || out.rounds > rounds_before + 1) break;  // a later round's failure keeps the start gains, as always
  }
  if (!settled) return start;
  out.gains = *settled;
  out.kept_start = false;
  out.settled_grey_ratio = out.start_grey_ratio;
  if (out.start_grey_ratio > kGreyRatio) {  // settled at a looser tolerance: on at the strict one, if it finds enough
    AutoWhiteBalanceReport strict = out;
    if (const auto refined = SettleOnGrey(usable, ccm, start, *settled, kGreyRatio, strict)) {
      out.gains = *refined;
      out.grey_fraction = strict.grey_fraction;
      out.settled_grey_ratio = kGreyRatio;
    }
    out.rounds = strict.rounds;
  }
  return out.gains;
}

std::array<float, 4> BayerPhaseGains(BayerPattern pattern, const std::array<double, 3>& gains) {
  std::array<float, 4> phase_gains{};
  const std::array<int, 4> colours = TileColours(pattern);
  for (std::size_t phase = 0; phase < 4; ++phase)
    phase_gains[phase] = static_cast<float>(gains[static_cast<std::size_t>(colours[phase])]);
  return phase_gains;
}

std::array<double, 3> EstimateMosaicWhiteBalance(const cv::Mat& codes, BayerPattern pattern, double black,
                                                 const std::array<double, 9>& ccm, const std::array<double, 3>& start,
                                                 AutoWhiteBalanceReport* report) {
  if (codes.type() != CV_32FC1 || codes.rows < 2 || codes.cols < 2)
    throw Error("mosaic white balance: need a float Bayer mosaic of at least one tile");
  const int rows = codes.rows / 2, cols = codes.cols / 2;
  const std::array<int, 4> colours = TileColours(pattern);
  const float black_level = static_cast<float>(black);
  cv::Mat rgb(rows, cols, CV_32FC3), brightness(rows, cols, CV_32FC1);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < rows; ++y) {
    const float* top = codes.ptr<float>(2 * y);
    const float* bottom = codes.ptr<float>(2 * y + 1);
    float* out = rgb.ptr<float>(y);
    float* lum = brightness.ptr<float>(y);
    for (int x = 0; x < cols; ++x) {
      float sum[3] = {0.0f, 0.0f, 0.0f};
      const float tile[4] = {top[2 * x], top[2 * x + 1], bottom[2 * x], bottom[2 * x + 1]};
      for (std::size_t phase = 0; phase < 4; ++phase) sum[colours[phase]] += tile[phase] - black_level;
      out[3 * x] = sum[0];
      out[3 * x + 1] = 0.5f * sum[1];
      out[3 * x + 2] = sum[2];
      lum[x] = 0.25f * (sum[0] + sum[1] + sum[2]);
    }
  }
  // The brightest tile within 7 tiles (an F01 micro-lens is 5 tiles across, an Illum's 7): a tile at half of it or
  // more is well inside its micro-image, as a white image of 0.5 or more marks in the decode.
  cv::Mat local_peak;
  cv::dilate(brightness, local_peak, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(15, 15)));
  cv::Mat lit(rows, cols, CV_32FC1);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < rows; ++y) {
    const float* b = brightness.ptr<float>(y);
    const float* peak = local_peak.ptr<float>(y);
    float* out = lit.ptr<float>(y);
    for (int x = 0; x < cols; ++x) out[x] = peak[x] > 0.0f && b[x] >= 0.5f * peak[x] ? 1.0f : 0.0f;
  }
  return EstimateWhiteBalance(rgb, lit, ccm, start, report);
}

}  // namespace lfsp::decode
