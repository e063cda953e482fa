#include "lfsp/simulate/evaluation_masks.h"

#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>

#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"

namespace lfsp::simulate {
namespace {

// 0 on both pixels of every 4-neighbour pair that hits two objects more than `jump` apart, 255 elsewhere (the
// input cv::distanceTransform measures from).
cv::Mat NotAtObjectJumps(const cv::Mat& objects, const DisparityMap& disparity, double jump) {
  cv::Mat not_jump(objects.rows, objects.cols, CV_8U, cv::Scalar(255));
  const auto mark_step = [&](int y0, int x0, int y1, int x1) {
    if (objects.at<std::int32_t>(y0, x0) == objects.at<std::int32_t>(y1, x1)) return;
    if (!(std::abs(disparity.at(y0, x0) - disparity.at(y1, x1)) > jump)) return;
    not_jump.at<unsigned char>(y0, x0) = 0;
    not_jump.at<unsigned char>(y1, x1) = 0;
  };
  for (int y = 0; y < objects.rows; ++y)
    for (int x = 0; x < objects.cols; ++x) {
      if (x + 1 < objects.cols) mark_step(y, x, y, x + 1);
      if (y + 1 < objects.rows) mark_step(y, x, y + 1, x);
    }
  return not_jump;
}

bool IsCurved(const Scene& scene, std::int32_t object) {
  return object >= 0 && scene.objects[static_cast<std::size_t>(object)].geometry == SceneObject::Geometry::kEllipsoid;
}

}  // namespace

SceneEvaluationMasks EvaluationMasksOf(const RenderedLightField& rendered, const Scene& scene, double jump,
                                       double radius) {
  const cv::Mat& objects = rendered.centre_objects;
  if (objects.empty() || objects.type() != CV_32S || objects.cols != rendered.disparity.width() ||
      objects.rows != rendered.disparity.height())
    throw Error("simulate: evaluation masks need the centre view's object map of the rendered light field");
  SceneEvaluationMasks masks;
  cv::Mat distance;
  cv::distanceTransform(NotAtObjectJumps(objects, rendered.disparity, jump), distance, cv::DIST_L2,
                        cv::DIST_MASK_PRECISE);
  cv::compare(distance, radius, masks.discontinuities, cv::CMP_LE);
  masks.planes = cv::Mat(objects.size(), CV_8U, cv::Scalar(0));
  masks.smooth_surfaces = cv::Mat(objects.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < objects.rows; ++y)
    for (int x = 0; x < objects.cols; ++x) {
      if (masks.discontinuities.at<unsigned char>(y, x) != 0) continue;
      cv::Mat& region = IsCurved(scene, objects.at<std::int32_t>(y, x)) ? masks.smooth_surfaces : masks.planes;
      region.at<unsigned char>(y, x) = 255;
    }
  return masks;
}

void WriteEvaluationMasks(const SceneEvaluationMasks& masks, const std::filesystem::path& folder) {
  const cv::Mat* maps[] = {&masks.discontinuities, &masks.planes, &masks.smooth_surfaces};
  for (std::size_t i = 0; i < kEvaluationMaskFiles.size(); ++i) WriteImage(*maps[i], folder / kEvaluationMaskFiles[i]);
}

}  // namespace lfsp::simulate
