#include "lfsp/decode/demosaic.h"

#include <omp.h>

#include <algorithm>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "lfsp/core/error.h"

namespace lfsp::decode {
namespace {

// OpenCV names a Bayer pattern by the second row's second and third pixels, so its names are the "opposite" of the
// top-left tile: an RGGB sensor is COLOR_BayerBG.
int OpenCvCode(BayerPattern pattern, bool edge_aware) {
  switch (pattern) {
    case BayerPattern::kRGGB:
      return edge_aware ? cv::COLOR_BayerBG2RGB_EA : cv::COLOR_BayerBG2RGB;
    case BayerPattern::kGRBG:
      return edge_aware ? cv::COLOR_BayerGB2RGB_EA : cv::COLOR_BayerGB2RGB;
    case BayerPattern::kGBRG:
      return edge_aware ? cv::COLOR_BayerGR2RGB_EA : cv::COLOR_BayerGR2RGB;
    case BayerPattern::kBGGR:
      return edge_aware ? cv::COLOR_BayerRG2RGB_EA : cv::COLOR_BayerRG2RGB;
  }
  return cv::COLOR_BayerBG2RGB;
}

cv::Mat DemosaicOpenCv(const cv::Mat& bayer, BayerPattern pattern, bool edge_aware, float max_value) {
  const double scale = 65535.0 / max_value;
  cv::Mat sixteen;
  bayer.convertTo(sixteen, CV_16U, scale);  // saturates above max_value
  cv::Mat rgb16;
  cv::demosaicing(sixteen, rgb16, OpenCvCode(pattern, edge_aware));
  cv::Mat rgb;
  rgb16.convertTo(rgb, CV_32F, 1.0 / scale);
  return rgb;
}

// Colour (0 r, 1 g, 2 b) at each phase 2 * (y & 1) + (x & 1).
std::array<int, 4> Tile(BayerPattern pattern) {
  switch (pattern) {
    case BayerPattern::kRGGB:
      return {0, 1, 1, 2};
    case BayerPattern::kGRBG:
      return {1, 0, 2, 1};
    case BayerPattern::kGBRG:
      return {1, 2, 0, 1};
    case BayerPattern::kBGGR:
      return {2, 1, 1, 0};
  }
  return {0, 1, 1, 2};
}

// Malvar-He-Cutler: bilinear interpolation corrected by the Laplacian of the known channel (5x5 kernels).
cv::Mat DemosaicGradient(const cv::Mat& bayer, BayerPattern pattern) {
  cv::Mat padded;
  // Mirroring about the edge pixel keeps the Bayer phase of every padded pixel.
  cv::copyMakeBorder(bayer, padded, 2, 2, 2, 2, cv::BORDER_REFLECT_101);
  const std::array<int, 4> tile = Tile(pattern);
  cv::Mat rgb(bayer.rows, bayer.cols, CV_32FC3);
  const int stride = static_cast<int>(padded.step1());
#pragma omp parallel for schedule(static)
  for (int y = 0; y < bayer.rows; ++y) {
    const float* row = padded.ptr<float>(y + 2) + 2;
    float* out = rgb.ptr<float>(y);
    for (int x = 0; x < bayer.cols; ++x) {
      const float* p = row + x;
      auto at = [p, stride](int dy, int dx) { return p[dy * stride + dx]; };
      const float c = p[0];
      const int colour = tile[static_cast<std::size_t>(2 * (y & 1) + (x & 1))];
      float r = 0.0f, g = 0.0f, b = 0.0f;
      const float axial = at(-1, 0) + at(1, 0) + at(0, -1) + at(0, 1);
      const float axial2 = at(-2, 0) + at(2, 0) + at(0, -2) + at(0, 2);
      const float diagonal = at(-1, -1) + at(-1, 1) + at(1, -1) + at(1, 1);
      if (colour == 1) {
        g = c;
        // Green pixel: one of red/blue is left-right, the other up-down.
        const float horizontal = (5.0f * c + 4.0f * (at(0, -1) + at(0, 1)) - (at(0, -2) + at(0, 2)) - diagonal +
                                  0.5f * (at(-2, 0) + at(2, 0))) *
                                 0.125f;
        const float vertical = (5.0f * c + 4.0f * (at(-1, 0) + at(1, 0)) - (at(-2, 0) + at(2, 0)) - diagonal +
                                0.5f * (at(0, -2) + at(0, 2))) *
                               0.125f;
        const int left_colour = tile[static_cast<std::size_t>(2 * (y & 1) + ((x + 1) & 1))];
        if (left_colour == 0) {
          r = horizontal;
          b = vertical;
        } else {
          b = horizontal;
          r = vertical;
        }
      } else {
        const float green = (4.0f * c + 2.0f * axial - axial2) * 0.125f;
        const float opposite = (6.0f * c + 2.0f * diagonal - 1.5f * axial2) * 0.125f;
        g = green;
        if (colour == 0) {
          r = c;
          b = opposite;
        } else {
          b = c;
          r = opposite;
        }
      }
      out[3 * x] = std::max(0.0f, r);
      out[3 * x + 1] = std::max(0.0f, g);
      out[3 * x + 2] = std::max(0.0f, b);
    }
  }
  return rgb;
}

}  // namespace

std::string_view ToString(DemosaicMethod method) {
  switch (method) {
    case DemosaicMethod::kBilinear:
      return "bilinear";
    case DemosaicMethod::kEdgeAware:
      return "edge-aware";
    case DemosaicMethod::kGradient:
      return "gradient";
  }
  return "?";
}

DemosaicMethod DemosaicMethodFromString(const std::string& name) {
  for (const DemosaicMethod method : {DemosaicMethod::kBilinear, DemosaicMethod::kEdgeAware, DemosaicMethod::kGradient})
    if (name == ToString(method)) return method;
  throw Error("demosaic method '" + name + "': unknown (expected bilinear, edge-aware or gradient)");
}

cv::Mat Demosaic(const cv::Mat& bayer, BayerPattern pattern, DemosaicMethod method, float max_value) {
  if (bayer.type() != CV_32FC1 || bayer.rows < 4 || bayer.cols < 4)
    throw Error("demosaic: expected a single-channel float Bayer image of at least 4x4 pixels");
  switch (method) {
    case DemosaicMethod::kBilinear:
      return DemosaicOpenCv(bayer, pattern, false, max_value);
    case DemosaicMethod::kEdgeAware:
      return DemosaicOpenCv(bayer, pattern, true, max_value);
    case DemosaicMethod::kGradient:
      return DemosaicGradient(bayer, pattern);
  }
  throw Error("demosaic: unknown method");
}

}  // namespace lfsp::decode
