#include "lfsp/segment/output.h"

#include <cstdio>
#include <opencv2/core.hpp>

#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"

namespace lfsp::segment {

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
    WriteImage(out, folder / name, 16);
  }
}

nlohmann::json PlanesToJson(const std::vector<Plane>& planes) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t k = 0; k < planes.size(); ++k) {
    out.push_back({{"label", k}, {"a", planes[k].a}, {"b", planes[k].b}, {"c", planes[k].c}});
  }
  return out;
}

}  // namespace lfsp::segment
