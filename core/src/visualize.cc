#include "lfsp/core/visualize.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "lfsp/core/error.h"

namespace lfsp {
cv::Mat DisplayEncoded(const cv::Mat& image, Transfer transfer) {
  if (image.empty() || image.depth() != CV_32F) throw Error("preview: expected a non-empty float image");
  cv::Mat out = image.clone();
  float* values = out.ptr<float>(0);
  const std::size_t count = out.total() * static_cast<std::size_t>(out.channels());
  for (std::size_t i = 0; i < count; ++i) {
    float value = std::clamp(values[i], 0.0f, 1.0f);
    if (transfer == Transfer::kLinear) value = LinearToSrgb(value);
    values[i] = value;
  }
  return out;
}

cv::Mat DisplayRgb8(const cv::Mat& view, Transfer transfer) {
  cv::Mat encoded = DisplayEncoded(view, transfer);
  if (encoded.channels() == 1) cv::cvtColor(encoded, encoded, cv::COLOR_GRAY2RGB);
  cv::Mat out;
  encoded.convertTo(out, CV_8U, 255.0);
  return out;
}

cv::Mat ColourMapDisparity(const DisparityMap& disparity, std::optional<DisparityRange> range) {
  const cv::Mat values = disparity.Mat();
  if (!range) {
    float lo = std::numeric_limits<float>::infinity();
    float hi = -lo;
    for (int i = 0; i < disparity.width() * disparity.height(); ++i) {
      const float d = disparity.data()[i];
      if (!std::isfinite(d)) continue;
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    range = DisparityRange{std::isfinite(lo) ? lo : 0.0f, std::isfinite(hi) ? hi : 1.0f};
  }
  const float span = std::max(range->max - range->min, 1e-6f);
  cv::Mat gray(values.size(), CV_8UC1);
  cv::Mat invalid(values.size(), CV_8UC1);
  for (int y = 0; y < values.rows; ++y)
    for (int x = 0; x < values.cols; ++x) {
      const float d = values.at<float>(y, x);
      invalid.at<uchar>(y, x) = std::isfinite(d) ? 0 : 255;
      const float t = std::isfinite(d) ? std::clamp((d - range->min) / span, 0.0f, 1.0f) : 0.0f;
      gray.at<uchar>(y, x) = static_cast<uchar>(std::lround(t * 255.0f));
    }
  cv::Mat bgr;
  cv::applyColorMap(gray, bgr, cv::COLORMAP_TURBO);
  bgr.setTo(cv::Scalar::all(0), invalid);
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  return rgb;
}

namespace {

template <typename T, typename Source>
cv::Mat HorizontalEpiOf(const Source& source, int y, int v, int type) {
  const LightFieldShape& shape = source.shape();
  if (y < 0 || y >= shape.height || v < 0 || v >= shape.nv) throw Error("horizontal EPI row out of range");
  cv::Mat epi(shape.nu, shape.width, type);
  const std::size_t row_bytes = static_cast<std::size_t>(shape.width) * shape.channels * sizeof(T);
  for (int u = 0; u < shape.nu; ++u) std::memcpy(epi.ptr<T>(u), &source.at({u, v}, y, 0, 0), row_bytes);
  return epi;
}

template <typename T, typename Source>
cv::Mat VerticalEpiOf(const Source& source, int x, int u, int type) {
  const LightFieldShape& shape = source.shape();
  if (x < 0 || x >= shape.width || u < 0 || u >= shape.nu) throw Error("vertical EPI column out of range");
  cv::Mat epi(shape.height, shape.nv, type);
  for (int v = 0; v < shape.nv; ++v)
    for (int y = 0; y < shape.height; ++y)
      std::memcpy(epi.ptr<T>(y) + static_cast<std::size_t>(v) * shape.channels, &source.at({u, v}, y, x, 0),
                  static_cast<std::size_t>(shape.channels) * sizeof(T));
  return epi;
}

}  // namespace

cv::Mat HorizontalEpi(const LightField& light_field, int y, int v) {
  return HorizontalEpiOf<float>(light_field, y, v, CV_MAKETYPE(CV_32F, light_field.shape().channels));
}
cv::Mat VerticalEpi(const LightField& light_field, int x, int u) {
  return VerticalEpiOf<float>(light_field, x, u, CV_MAKETYPE(CV_32F, light_field.shape().channels));
}
cv::Mat HorizontalEpi(const Labels& labels, int y, int v) {
  return HorizontalEpiOf<std::int32_t>(labels, y, v, CV_32SC1);
}
cv::Mat VerticalEpi(const Labels& labels, int x, int u) { return VerticalEpiOf<std::int32_t>(labels, x, u, CV_32SC1); }

cv::Mat DrawLabelBoundaries(const cv::Mat& rgb8, const cv::Mat& labels, cv::Vec3b colour) {
  if (rgb8.size() != labels.size() || labels.type() != CV_32SC1 || rgb8.type() != CV_8UC3)
    throw Error("DrawLabelBoundaries: needs an 8-bit RGB image and CV_32SC1 labels of the same size");
  cv::Mat out = rgb8.clone();
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x) {
      const int label = labels.at<int>(y, x);
      const bool right = x + 1 < labels.cols && labels.at<int>(y, x + 1) != label;
      const bool down = y + 1 < labels.rows && labels.at<int>(y + 1, x) != label;
      if (right || down) out.at<cv::Vec3b>(y, x) = colour;
    }
  return out;
}

cv::Mat Enlarge(const cv::Mat& image, int factor_x, int factor_y) {
  cv::Mat out;
  cv::resize(image, out, cv::Size(image.cols * factor_x, image.rows * factor_y), 0, 0, cv::INTER_NEAREST);
  return out;
}

int DefaultEpiStretch(const LightFieldShape& shape) {
  return std::max(4, 96 / std::max(1, std::max(shape.nu, shape.nv)));
}

cv::Mat CentreViewBoundaries(const LightField& light_field, const Labels& labels) {
  RequireLabelsMatch(labels, light_field.shape(), "segmentation picture");
  const ViewIndex centre = light_field.shape().Centre();
  return DrawLabelBoundaries(DisplayRgb8(light_field.View(centre), light_field.transfer), labels.View(centre));
}

cv::Mat HorizontalEpiBoundaries(const LightField& light_field, const Labels& labels, int y, int stretch) {
  RequireLabelsMatch(labels, light_field.shape(), "segmentation picture");
  const int v = light_field.shape().Centre().v;
  const cv::Mat picture = DrawLabelBoundaries(DisplayRgb8(HorizontalEpi(light_field, y, v), light_field.transfer),
                                              HorizontalEpi(labels, y, v));
  return Enlarge(picture, 1, stretch > 0 ? stretch : DefaultEpiStretch(light_field.shape()));
}

cv::Mat VerticalEpiBoundaries(const LightField& light_field, const Labels& labels, int x, int stretch) {
  RequireLabelsMatch(labels, light_field.shape(), "segmentation picture");
  const int u = light_field.shape().Centre().u;
  const cv::Mat picture =
      DrawLabelBoundaries(DisplayRgb8(VerticalEpi(light_field, x, u), light_field.transfer), VerticalEpi(labels, x, u));
  return Enlarge(picture, stretch > 0 ? stretch : DefaultEpiStretch(light_field.shape()), 1);
}

std::vector<cv::Mat> ViewSweepFrames(const LightField& light_field) {
  const LightFieldShape& shape = light_field.shape();
  const ViewIndex centre = shape.Centre();
  std::vector<cv::Mat> frames;
  for (int u = 0; u < shape.nu; ++u)
    frames.push_back(DisplayRgb8(light_field.View({u, centre.v}), light_field.transfer));
  for (int v = 0; v < shape.nv; ++v)
    frames.push_back(DisplayRgb8(light_field.View({centre.u, v}), light_field.transfer));
  return frames;
}

}  // namespace lfsp
