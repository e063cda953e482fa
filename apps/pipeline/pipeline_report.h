#pragma once

#include "../report/html_report.h"
#include "lfsp/core/light_field.h"
#include "lfsp/depth/depth_estimator.h"
#include "lfsp/segment/lfsp.h"
#include "pipeline.h"

namespace lfsp::pipeline {

struct ReportInputs {
  const LightField& light_field;
  const depth::DepthResult& depth;
  const segment::LfspResult& segmentation;
  const DisparityMap* ground_truth_disparity;  // may be null
};

// The figures of report.html: centre view, a sweep through the views, depth, LFSP boundaries on the centre view and
// on a horizontal and a vertical EPI. Metrics and timings are filled in by the caller.
report::Report BuildReport(const ReportInputs& inputs, const PipelineOptions& options);

}  // namespace lfsp::pipeline
