#pragma once

#include <opencv2/core/types.hpp>
#include <string>
#include <vector>

#include "lfsp/edit/recolor.h"

namespace lfsp::pipeline {

// The pipeline's `--recolor SPEC`: semicolon-separated key=value pairs, e.g.
//   "at=120,80;hue=140"                  the superpixel under centre-view pixel (x=120, y=80), hue +140 degrees
//   "at=10,20+30,40;saturation=0;value=1.2;feather=2"
//   "ids=3+17;hue=-60;space=hsv"
// keys: at (x,y points joined by '+'), ids (label ids joined by '+'), hue (degrees), saturation, value (factors),
// feather (pixels), space (lch or hsv). `at` or `ids` is required.
struct RecolorSpec {
  std::vector<cv::Point> points;
  std::vector<int> ids;
  edit::RecolorOptions options;
};

RecolorSpec ParseRecolorSpec(const std::string& text);  // throws lfsp::Error naming the bad part

}  // namespace lfsp::pipeline
