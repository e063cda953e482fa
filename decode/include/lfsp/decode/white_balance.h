#pragma once

// White balance of `--colour camera` decodes: the camera's own gains (Lytro files carry them), none, gains given by
// the user, or an automatic estimate from the capture's own near-grey pixels (for plain raw images, whose gains are
// not known: the nominal camera's gains belong to another scene's light).

#include <array>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>

#include "lfsp/decode/lytro_metadata.h"

namespace lfsp::decode {

enum class WhiteBalanceMode { kCamera, kAuto, kNone, kGains };

struct WhiteBalance {
  WhiteBalanceMode mode = WhiteBalanceMode::kCamera;
  std::array<double, 3> gains = {1.0, 1.0, 1.0};  // R, G, B; kGains only
};

// "camera", "auto", "none" or three positive gains "R,G,B" (scaled so that G is 1); lfsp::Error naming the option
// otherwise.
WhiteBalance WhiteBalanceFromString(const std::string& text);
std::string ToString(const WhiteBalance& balance);

// The metadata's white-balance gains relative to green (image.color.whiteBalanceGain), or 1, 1, 1 without them.
std::array<double, 3> CameraWhiteBalanceGains(const LytroMetadata& metadata);

// The metadata's colour matrix (row-major, applied to white-balanced sensor RGB), or the identity without one.
std::array<double, 9> CameraColourMatrix(const LytroMetadata& metadata);

struct AutoWhiteBalanceReport {
  std::array<double, 3> start = {1.0, 1.0, 1.0};  // gains the search began from (the camera's)
  std::array<double, 3> gains = {1.0, 1.0, 1.0};  // what it settled on
  // Grey tolerances (largest over smallest channel): the one the search started at (1.3, or a looser one when too few
  // pixels were within 1.3x under the start gains; the last one tried when it kept the start gains), and the one the
  // gains settled at (1.3 again after a looser start, unless too few pixels were grey there; 0 when the start gains
  // were kept).
  double start_grey_ratio = 1.3;
  double settled_grey_ratio = 0.0;
  // Share of the well-lit pixels taken as grey in the last round at the settled tolerance (start gains kept: in the
  // round that found too few).
  double grey_fraction = 0.0;
  int rounds = 0;
  bool kept_start = false;  // too few grey pixels: the start gains were kept
  nlohmann::json ToJson() const;
};

// Gains (R, G, B with G = 1) that make the capture's near-grey surfaces grey, in the manner of Huo et al., "Robust
// automatic white balance algorithm using gray color points in images" (IEEE Trans. Consumer Electronics, 2006):
// starting from `start`, the well-lit, unclipped pixels whose colour after the gains and `ccm` is close to neutral
// (channels within 1.3x) are averaged in sensor RGB, the gains are set to make that average grey, and the selection is
// repeated until the gains settle. Coloured scenes (foliage) keep their colour: only pixels near grey vote. When too
// few are within 1.3x under `start` (a light far from the one `start` was made for), a looser tolerance (1.6, then
// 2.0) finds the least coloured surfaces first, and the search goes on at 1.3 from there. `rgb` is the devignetted,
// demosaicked sensor image (CV_32FC3, R G B), `grey_white` its white image (CV_32FC1, 1 at the micro-image peak): only
// pixels with white >= 0.5 are used.
std::array<double, 3> EstimateWhiteBalance(const cv::Mat& rgb, const cv::Mat& grey_white,
                                           const std::array<double, 9>& ccm, const std::array<double, 3>& start,
                                           AutoWhiteBalanceReport* report = nullptr);

// The same estimate from a Bayer mosaic before any decoding (`codes` CV_32FC1, `black` its black level in the same
// codes): each 2x2 tile is one RGB pixel (its two greens averaged), and the tiles at least half as bright as the
// brightest within 7 tiles stand for the white image's well-lit pixels. Close to the estimate on the decoded views,
// not equal. With `--jpeg-grey scene` it is what a JPEG mosaic's restoration takes for grey, and the decode's
// automatic white balance (raw_input.cc).
std::array<double, 3> EstimateMosaicWhiteBalance(const cv::Mat& codes, BayerPattern pattern, double black,
                                                 const std::array<double, 9>& ccm, const std::array<double, 3>& start,
                                                 AutoWhiteBalanceReport* report = nullptr);

// Gains per position of the 2x2 tile (row by row) from gains per colour (R, G, B).
std::array<float, 4> BayerPhaseGains(BayerPattern pattern, const std::array<double, 3>& gains);

}  // namespace lfsp::decode
