#include "initialisation.h"

#include <Eigen/Dense>
#include <cmath>
#include <opencv2/calib3d.hpp>

#include "lfsp/core/error.h"

namespace lfsp::calibrate::internal {
namespace {

// Homography from board metres to centred pixels of one view.
Eigen::Matrix3d BoardHomography(const CaptureCorners& capture, const ViewCorners& view, double square_size) {
  const Eigen::Vector4d centre = CentreIndex(capture.shape);
  std::vector<cv::Point2d> board, pixels;
  for (int b = 0; b < capture.corners_y; ++b)
    for (int a = 0; a < capture.corners_x; ++a) {
      board.emplace_back(a * square_size, b * square_size);
      const cv::Point2d& p = view.corners[static_cast<std::size_t>(b * capture.corners_x + a)];
      pixels.emplace_back(p.x - centre(0), p.y - centre(1));
    }
  const cv::Mat h = cv::findHomography(board, pixels, 0);
  if (h.empty()) throw Error(capture.name + ": no homography fits the corners of its reference view");
  Eigen::Matrix3d out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = h.at<double>(r, c);
  return out / out.norm();
}

// 1 / f^2 from the constraints h1' W h2 = 0 and h1' W h1 = h2' W h2 with W = diag(1/f^2, 1/f^2, 1).
double InverseFocalSquared(const std::vector<Eigen::Matrix3d>& homographies) {
  double ab = 0, aa = 0;
  for (const auto& h : homographies) {
    const double a1 = h(0, 0) * h(0, 1) + h(1, 0) * h(1, 1), b1 = -h(2, 0) * h(2, 1);
    const double a2 = h(0, 0) * h(0, 0) + h(1, 0) * h(1, 0) - h(0, 1) * h(0, 1) - h(1, 1) * h(1, 1);
    const double b2 = -(h(2, 0) * h(2, 0) - h(2, 1) * h(2, 1));
    ab += a1 * b1 + a2 * b2;
    aa += a1 * a1 + a2 * a2;
  }
  return aa > 0 ? ab / aa : 0;
}

Pose PoseFromHomography(const Eigen::Matrix3d& h, double focal) {
  const Eigen::Matrix3d k_inverse = Eigen::Vector3d(1 / focal, 1 / focal, 1).asDiagonal();
  const Eigen::Matrix3d m = k_inverse * h;
  double lambda = 2.0 / (m.col(0).norm() + m.col(1).norm());
  if (m(2, 2) * lambda < 0) lambda = -lambda;  // the board is in front of the camera
  Eigen::Matrix3d r;
  r.col(0) = lambda * m.col(0);
  r.col(1) = lambda * m.col(1);
  r.col(2) = r.col(0).cross(r.col(1));
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d rotation = svd.matrixU() * svd.matrixV().transpose();
  if (rotation.determinant() < 0) rotation = -rotation;
  const Eigen::AngleAxisd aa(rotation);
  const Eigen::Vector3d axis = aa.angle() * aa.axis();
  const Eigen::Vector3d t = lambda * m.col(2);
  return {axis(0), axis(1), axis(2), t(0), t(1), t(2)};
}

}  // namespace

InitialEstimate InitialiseFromHomographies(const std::vector<CaptureCorners>& captures,
                                           const std::vector<Observation>& observations, double square_size) {
  std::vector<Eigen::Matrix3d> homographies;
  for (const auto& capture : captures) {
    const ViewCorners* reference = nullptr;
    for (const auto& view : capture.views)
      if (view.view == capture.reference) reference = &view;
    if (reference == nullptr) reference = &capture.views.front();
    homographies.push_back(BoardHomography(capture, *reference, square_size));
  }
  const double w = InverseFocalSquared(homographies);
  if (!(w > 0)) {
    throw Error(
        "calibration: the focal length cannot be initialised from these captures: tilt the board more (15-45 "
        "degrees) and vary the tilt direction between captures");
  }
  const double focal = 1.0 / std::sqrt(w);

  InitialEstimate estimate;
  for (const auto& h : homographies) estimate.poses.push_back(PoseFromHomography(h, focal));

  // Linear least squares for the slopes, horizontal and vertical separately.
  Eigen::Matrix3d ax = Eigen::Matrix3d::Zero(), ay = Eigen::Matrix3d::Zero();
  Eigen::Vector3d bx = Eigen::Vector3d::Zero(), by = Eigen::Vector3d::Zero();
  for (const auto& o : observations) {
    const Pose& pose = estimate.poses[static_cast<std::size_t>(o.capture)];
    const Eigen::Vector3d axis(pose[0], pose[1], pose[2]);
    const double angle = axis.norm();
    const Eigen::Matrix3d r =
        angle > 0 ? Eigen::AngleAxisd(angle, axis / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
    const Eigen::Vector3d p = r * Eigen::Vector3d(o.x, o.y, 0) + Eigen::Vector3d(pose[3], pose[4], pose[5]);
    const Eigen::Vector3d rx(o.i * p.z(), o.k * p.z(), o.k), ry(o.j * p.z(), o.l * p.z(), o.l);
    ax += rx * rx.transpose();
    bx += rx * p.x();
    ay += ry * ry.transpose();
    by += ry * p.y();
  }
  const Eigen::Vector3d hx = ax.ldlt().solve(bx), hy = ay.ldlt().solve(by);
  if (!hx.allFinite() || !hy.allFinite() || !(hx(0) > 0) || !(hy(0) > 0))
    throw Error("calibration: the linear initialisation of the intrinsic matrix failed (degenerate captures?)");
  estimate.slopes = {0.0, hx(2), hx(0), hx(1), 0.0, hy(2), hy(0), hy(1)};
  return estimate;
}

}  // namespace lfsp::calibrate::internal
