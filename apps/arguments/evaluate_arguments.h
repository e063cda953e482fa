#pragma once

#include <CLI/CLI.hpp>
#include <vector>

#include "lfsp/depth/metrics.h"
#include "lfsp/segment/evaluate.h"

namespace lfsp::cli {

// The options of `lfsp evaluate segmentation` that say what to score, as the command line and the Python module
// spell them.
struct SegmentationEvaluationArguments {
  bool baselines = false;
  bool no_refocus = false;
  std::vector<double> refocus_levels = segment::DefaultRefocusLevels();
  int tolerance = 2;
};

void AddSegmentationEvaluationArguments(CLI::App* command, SegmentationEvaluationArguments& arguments);
segment::EvaluationOptions ToEvaluationOptions(const SegmentationEvaluationArguments& arguments);

// The options of `lfsp evaluate depth`: --boundary, --jump, --near.
void AddDepthMetricArguments(CLI::App* command, depth::MetricOptions& metrics);

}  // namespace lfsp::cli
