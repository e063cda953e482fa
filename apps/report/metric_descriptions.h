#pragma once

#include <string>
#include <string_view>

namespace lfsp::report {

enum class Better { kHigher, kLower, kNeither };

// What a figure of a run's metrics means, for people: the one table of them (metric_descriptions.cc), read by the
// HTML report. `key` is the dotted path in the metrics JSON (summary.json's "metrics"), a '*' matching any one part.
struct MetricDescription {
  std::string_view key;
  std::string_view name;     // in words
  std::string_view unit;     // "" for a plain number
  Better better;             // which direction is better
  std::string_view meaning;  // one line
  std::string_view source;   // the paper the figure comes from ("" for lfsp's own)
};

// The description of a dotted metrics key, or null when the table has none (the report then shows the key itself).
const MetricDescription* DescribeMetric(std::string_view dotted_key);

// The title of a top-level group of metrics ("depth" -> "Depth against the true disparity"), or "" if unknown.
std::string_view DescribeGroup(std::string_view group);

// The words for a part of a key that names where a figure was measured, e.g. "near_discontinuities" -> "near depth
// edges", or "" when the part is not such a qualifier.
std::string_view DescribeRegion(std::string_view part);

}  // namespace lfsp::report
