#pragma once

#include <opencv2/core/mat.hpp>
#include <string>
#include <string_view>

#include "lfsp/decode/lytro_metadata.h"

namespace lfsp::decode {

// Demosaicking methods compared by the decoder (tests/decode/decode_test.cc measures them on a simulated capture;
// the decoder defaults to the best):
//   kBilinear     OpenCV's bilinear interpolation (on 16-bit data)
//   kEdgeAware    OpenCV's edge-aware method (COLOR_Bayer*2RGB_EA, on 16-bit data)
//   kGradient     gradient-corrected bilinear (Malvar, He & Cutler 2004; what MATLAB's demosaic and LFToolbox use),
//                 in float, no quantisation
enum class DemosaicMethod { kBilinear, kEdgeAware, kGradient };
std::string_view ToString(DemosaicMethod method);
DemosaicMethod DemosaicMethodFromString(const std::string& name);  // lfsp::Error on an unknown name

// The micro-image layout of a lenslet capture, for demosaicking it: the white image as one grey image (micro-image
// centres at 1) and the label of the lens over each pixel (LensLabels).
struct MicroImages {
  const cv::Mat& white_grey;
  const cv::Mat& lens_labels;
};

// Demosaics a single-channel float Bayer image (values >= 0, any scale up to `max_value`) into an interleaved RGB
// float image (CV_32FC3, R first). Parallel. With `micro_images`, kGradient keeps to each micro-image: near its edge
// it falls back to bilinear over the neighbours under the same lens, so no neighbouring micro-image leaks into the
// outer views; it prefers pairs of neighbours wholly under the lens, and where only the inner one of every pair is,
// it carries the pixel's own channel's change across (tests/decode/demosaic_test.cc), so the outer views keep their
// place.
cv::Mat Demosaic(const cv::Mat& bayer, BayerPattern pattern, DemosaicMethod method, float max_value = 4.0f,
                 const MicroImages* micro_images = nullptr);

}  // namespace lfsp::decode
