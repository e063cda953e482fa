#include "lfsp/depth/occlusion.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "lfsp/core/conventions.h"
#include "lfsp/core/error.h"

namespace lfsp::depth {

int SectorOfOffset(int du, int dv) {
  const double angle = std::atan2(static_cast<double>(dv), static_cast<double>(du));
  const double step = 2.0 * std::numbers::pi / kSectors;
  const int sector = static_cast<int>(std::lround(angle / step));
  return ((sector % kSectors) + kSectors) % kSectors;
}

int SplitForEdgeNormal(double normal_radians) {
  // Half A of split j holds the sectors centred on j*step .. (j + kSectors/2 - 1)*step, so it is centred on
  // (j + (kSectors/2 - 1)/2) * step; choose j so that this centre is nearest to the normal.
  const double step = 2.0 * std::numbers::pi / kSectors;
  const double j = normal_radians / step - (kSectors / 2 - 1) / 2.0;
  const int split = static_cast<int>(std::lround(j));
  return ((split % kSplits) + kSplits) % kSplits;  // j and j + kSplits give the same two halves
}

int AlongPairForEdgeNormal(double normal_radians) {
  const double step = 2.0 * std::numbers::pi / kSectors;
  const int sector = static_cast<int>(std::lround((normal_radians + std::numbers::pi / 2.0) / step));
  return ((sector % (kSectors / 2)) + kSectors / 2) % (kSectors / 2);
}

namespace {

// How far the outermost views lie from the centre view along u and along v, in view steps. With an even view count
// the centre view (CentreView) sits left of the middle, so the far side is one step longer than (n - 1) / 2.
std::pair<int, int> OutermostOffsets(int nu, int nv) {
  const ViewIndex centre = CentreView(nu, nv);
  return {std::max(centre.u, nu - 1 - centre.u), std::max(centre.v, nv - 1 - centre.v)};
}

}  // namespace

double AutomaticOcclusionRadius(int nu, int nv, float disparity_min, float disparity_max, double presmooth_sigma) {
  const auto [along_u, along_v] = OutermostOffsets(nu, nv);
  const double offset = std::max(along_u, along_v);
  return std::clamp(offset * static_cast<double>(disparity_max - disparity_min), 2.0, kMaxAutomaticOcclusionRadius) +
         2.0 * std::max(presmooth_sigma, 0.0);
}

double LongestViewOffset(int nu, int nv) {
  const auto [along_u, along_v] = OutermostOffsets(nu, nv);
  return std::hypot(along_u, along_v);
}

namespace {

// The structure tensor of the view as given (not blurred like Canny's input): its forward differences' products
// summed over the channels and averaged over a Gaussian window. Forward differences see a 1 px comb at full
// contrast, where the central differences of a Sobel kernel see nothing and a 1 px blur leaves 0.7 % of it.
class StructureTensor {
 public:
  StructureTensor(const cv::Mat& rgb, double window_sigma) {
    const cv::Mat forward_x = (cv::Mat_<float>(1, 2) << -1.0f, 1.0f);
    const cv::Mat forward_y = (cv::Mat_<float>(2, 1) << -1.0f, 1.0f);
    cv::Mat dx, dy;
    cv::filter2D(rgb, dx, CV_32F, forward_x, cv::Point(0, 0), 0.0, cv::BORDER_REPLICATE);
    cv::filter2D(rgb, dy, CV_32F, forward_y, cv::Point(0, 0), 0.0, cv::BORDER_REPLICATE);
    xx_ = WindowedChannelSum(dx.mul(dx), window_sigma);
    yy_ = WindowedChannelSum(dy.mul(dy), window_sigma);
    xy_ = WindowedChannelSum(dx.mul(dy), window_sigma);
  }

  // The dominant gradient direction at (x, y), radians from +x towards +y, modulo pi.
  double Direction(int y, int x) const {
    return 0.5 * std::atan2(2.0 * xy_.at<float>(y, x), xx_.at<float>(y, x) - yy_.at<float>(y, x));
  }

  // How much one direction dominates at (x, y): (l1 - l2) / (l1 + l2) of the tensor's eigenvalues, 1 along a
  // straight edge or a comb, 0 where gradients point every way (a corner, isotropic texture).
  double Coherence(int y, int x) const {
    const double xx = xx_.at<float>(y, x), yy = yy_.at<float>(y, x), xy = xy_.at<float>(y, x);
    const double trace = xx + yy;
    return trace > 0.0 ? std::sqrt((xx - yy) * (xx - yy) + 4.0 * xy * xy) / trace : 0.0;
  }

 private:
  static cv::Mat WindowedChannelSum(const cv::Mat& products, double window_sigma) {
    cv::Mat sum;
    cv::transform(products, sum, cv::Matx13f(1.0f, 1.0f, 1.0f));
    cv::GaussianBlur(sum, sum, cv::Size(), window_sigma);
    return sum;
  }

  cv::Mat xx_, yy_, xy_;
};

}  // namespace

int OcclusionMap::Candidates() const { return candidate.empty() ? 0 : cv::countNonZero(candidate); }

OcclusionMap DetectOcclusionEdges(const cv::Mat& centre_rgb, const OcclusionOptions& options) {
  if (centre_rgb.empty() || centre_rgb.type() != CV_32FC3) {
    throw Error("occlusion detection: the centre view must be a float RGB image");
  }
  if (!(options.radius > 0.0)) throw Error("occlusion detection: the radius must be positive");
  cv::Mat smooth;
  cv::GaussianBlur(centre_rgb, smooth, cv::Size(), options.blur_sigma);
  std::vector<cv::Mat> channels;
  cv::split(smooth, channels);

  // Edges: Canny on every channel, OR-ed. Orientation: gradient of the channel with the strongest response.
  cv::Mat edges(centre_rgb.size(), CV_8U, cv::Scalar(0));
  cv::Mat best_magnitude(centre_rgb.size(), CV_32F, cv::Scalar(0));
  cv::Mat normal(centre_rgb.size(), CV_32F, cv::Scalar(0));
  for (const cv::Mat& channel : channels) {
    cv::Mat channel8;
    channel.convertTo(channel8, CV_8U, 255.0);
    cv::Mat channel_edges;
    cv::Canny(channel8, channel_edges, options.canny_low, options.canny_high, 3, true);
    edges |= channel_edges;
    cv::Mat gx;
    cv::Mat gy;
    cv::Sobel(channel, gx, CV_32F, 1, 0, 3);
    cv::Sobel(channel, gy, CV_32F, 0, 1, 3);
    for (int y = 0; y < channel.rows; ++y) {
      for (int x = 0; x < channel.cols; ++x) {
        const float a = gx.at<float>(y, x);
        const float b = gy.at<float>(y, x);
        const float magnitude = a * a + b * b;
        if (magnitude > best_magnitude.at<float>(y, x)) {
          best_magnitude.at<float>(y, x) = magnitude;
          normal.at<float>(y, x) = std::atan2(b, a);
        }
      }
    }
  }

  const StructureTensor tensor(centre_rgb, options.along_window_sigma);

  // Every pixel inherits the split of its nearest edge pixel (distance transform with per-pixel labels).
  cv::Mat not_edge;
  cv::compare(edges, 0, not_edge, cv::CMP_EQ);
  cv::Mat distance;
  cv::Mat nearest;
  cv::distanceTransform(not_edge, distance, nearest, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_PIXEL);
  std::vector<unsigned char> split_of_label(static_cast<std::size_t>(edges.total()) + 1, 0);
  std::vector<unsigned char> along_of_label(split_of_label.size(), 0);
  for (int y = 0; y < edges.rows; ++y) {
    for (int x = 0; x < edges.cols; ++x) {
      if (edges.at<unsigned char>(y, x) == 0) continue;
      const int label = nearest.at<int>(y, x);
      split_of_label[static_cast<std::size_t>(label)] =
          static_cast<unsigned char>(SplitForEdgeNormal(normal.at<float>(y, x)));
      const bool oriented = tensor.Coherence(y, x) >= options.along_min_coherence;
      along_of_label[static_cast<std::size_t>(label)] = static_cast<unsigned char>(
          AlongPairForEdgeNormal(oriented ? tensor.Direction(y, x) : normal.at<float>(y, x)));
    }
  }
  OcclusionMap map;
  cv::compare(distance, options.radius, map.candidate, cv::CMP_LE);
  if (cv::countNonZero(edges) == 0) map.candidate.setTo(0);
  map.split = cv::Mat(edges.size(), CV_8U, cv::Scalar(0));
  map.along = cv::Mat(edges.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < edges.rows; ++y) {
    for (int x = 0; x < edges.cols; ++x) {
      const auto label = static_cast<std::size_t>(nearest.at<int>(y, x));
      map.split.at<unsigned char>(y, x) = split_of_label[label];
      map.along.at<unsigned char>(y, x) = along_of_label[label];
    }
  }
  return map;
}

}  // namespace lfsp::depth
