#include "lfsp/segment/output.h"

#include <cstdio>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"

namespace lfsp::segment {
namespace {

void WriteEncoded(const std::vector<uchar>& bytes, const std::filesystem::path& path) {
  AtomicOutput output(path);
  std::ofstream file(output.temporary(), std::ios::binary);
  file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  file.close();
  if (!file) ThrowFileError(path.string(), "could not write the PNG");
  output.Commit();
}

// 8-bit BGR copy of one view (display values).
cv::Mat DisplayView(const LightField& light_field, ViewIndex view) {
  cv::Mat rgb8, bgr;
  light_field.View(view).convertTo(rgb8, CV_8U, 255.0);
  cv::cvtColor(rgb8, bgr, light_field.shape().channels == 1 ? cv::COLOR_GRAY2BGR : cv::COLOR_RGB2BGR);
  return bgr;
}

// Marks in red every pixel whose right or lower neighbour has another label.
void DrawBoundaries(cv::Mat& bgr, const cv::Mat& labels) {
  for (int y = 0; y < labels.rows; ++y) {
    for (int x = 0; x < labels.cols; ++x) {
      const int k = labels.at<int>(y, x);
      const bool edge = (x + 1 < labels.cols && labels.at<int>(y, x + 1) != k) ||
                        (y + 1 < labels.rows && labels.at<int>(y + 1, x) != k);
      if (edge) bgr.at<cv::Vec3b>(y, x) = {0, 0, 255};
    }
  }
}

void CheckSameShape(const LightField& light_field, const Labels& labels) {
  const LightFieldShape& a = light_field.shape();
  const LightFieldShape& b = labels.shape();
  if (a.nu != b.nu || a.nv != b.nv || a.width != b.width || a.height != b.height) {
    throw Error("overlay: labels " + ToString(b) + " do not match the light field " + ToString(a));
  }
}

}  // namespace

void WritePng(const cv::Mat& image, const std::filesystem::path& path) {
  std::vector<uchar> bytes;
  if (!cv::imencode(".png", image, bytes)) ThrowFileError(path.string(), "PNG encoding failed");
  WriteEncoded(bytes, path);
}

void WriteLabelPngs(const Labels& labels, const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  const LightFieldShape& shape = labels.shape();
  for (int cam = 0; cam < static_cast<int>(shape.Views()); ++cam) {
    const cv::Mat view = labels.View(ViewFromCameraNumber(cam, shape.nu));
    cv::Mat out(view.size(), CV_16U);
    for (int y = 0; y < view.rows; ++y) {
      for (int x = 0; x < view.cols; ++x) {
        const int k = view.at<int>(y, x);
        if (k >= 65535) throw Error("label " + std::to_string(k) + " does not fit a 16-bit PNG");
        out.at<std::uint16_t>(y, x) = k < 0 ? 65535 : static_cast<std::uint16_t>(k);
      }
    }
    char name[32];
    std::snprintf(name, sizeof(name), "label_Cam%03d.png", cam);
    WritePng(out, folder / name);
  }
}

cv::Mat CentreOverlay(const LightField& light_field, const Labels& labels) {
  CheckSameShape(light_field, labels);
  const ViewIndex centre = light_field.shape().Centre();
  cv::Mat bgr = DisplayView(light_field, centre);
  DrawBoundaries(bgr, labels.View(centre));
  return bgr;
}

cv::Mat HorizontalEpiOverlay(const LightField& light_field, const Labels& labels, int y, int scale) {
  CheckSameShape(light_field, labels);
  const LightFieldShape& shape = light_field.shape();
  if (y < 0 || y >= shape.height) throw Error("EPI row " + std::to_string(y) + " is outside the views");
  cv::Mat epi(shape.nu * scale, shape.width, CV_8UC3), epi_labels(shape.nu * scale, shape.width, CV_32S);
  for (int u = 0; u < shape.nu; ++u) {
    const ViewIndex view{u, shape.Centre().v};
    const cv::Mat image = DisplayView(light_field, view);
    for (int r = 0; r < scale; ++r) {
      image.row(y).copyTo(epi.row(u * scale + r));
      labels.View(view).row(y).copyTo(epi_labels.row(u * scale + r));
    }
  }
  DrawBoundaries(epi, epi_labels);
  return epi;
}

cv::Mat VerticalEpiOverlay(const LightField& light_field, const Labels& labels, int x, int scale) {
  CheckSameShape(light_field, labels);
  const LightFieldShape& shape = light_field.shape();
  if (x < 0 || x >= shape.width) throw Error("EPI column " + std::to_string(x) + " is outside the views");
  cv::Mat epi(shape.height, shape.nv * scale, CV_8UC3), epi_labels(shape.height, shape.nv * scale, CV_32S);
  for (int v = 0; v < shape.nv; ++v) {
    const ViewIndex view{shape.Centre().u, v};
    const cv::Mat image = DisplayView(light_field, view);
    for (int c = 0; c < scale; ++c) {
      image.col(x).copyTo(epi.col(v * scale + c));
      labels.View(view).col(x).copyTo(epi_labels.col(v * scale + c));
    }
  }
  DrawBoundaries(epi, epi_labels);
  return epi;
}

nlohmann::json PlanesToJson(const std::vector<Plane>& planes) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t k = 0; k < planes.size(); ++k) {
    out.push_back({{"label", k}, {"a", planes[k].a}, {"b", planes[k].b}, {"c", planes[k].c}});
  }
  return out;
}

}  // namespace lfsp::segment
