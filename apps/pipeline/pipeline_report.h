#pragma once

#include "lfsp/core/light_field.h"
#include "lfsp/depth/depth_estimator.h"
#include "lfsp/segment/lfsp.h"
#include "pipeline.h"
#include "report/html_report.h"
#include "stages/recolor_stage.h"
#include "truth_comparison.h"

namespace lfsp::pipeline {

struct FocalStackFigures {
  std::vector<float> disparities;
  std::vector<cv::Mat> slices;  // float, the light field's transfer
};

struct ReportInputs {
  const LightField& light_field;
  const depth::DepthResult& depth;
  const segment::LfspResult& segmentation;
  const DisparityMap* ground_truth_disparity;  // may be null
  const stages::RecolorStageResult* recolor;   // may be null
  FocalStackFigures focal_stack;
  const TruthComparison* truth_comparison;  // a simulated capture's decode against its ideal light field; may be null
};

// The figures of report.html: centre view, a sweep through the views, depth, LFSP boundaries on the centre view and
// on a horizontal and a vertical EPI. Metrics and timings are filled in by the caller.
report::Report BuildReport(const ReportInputs& inputs, const PipelineOptions& options);

}  // namespace lfsp::pipeline
