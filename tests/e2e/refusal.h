#pragma once

// The bad-input promise as the hostile-input suites check it, in one place.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "test_support.h"

namespace lfsp::testing {

// 1 GiB: every hostile input of these suites is a few MB at most (the issues' bound for inputs under 1 MB).
inline constexpr long kSmallInputPeakKb = 1024L * 1024L;

// Exit 2, exactly one line on stderr that starts with "lfsp: error: " and names `named`, memory bounded.
inline void ExpectRefused(const CommandResult& result, const std::string& named) {
  EXPECT_EQ(result.exit_status, 2) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_EQ(result.err.rfind("lfsp: error: ", 0), 0u) << result.err;
  EXPECT_NE(result.err.find(named), std::string::npos) << "'" << result.err << "' does not name '" << named << "'";
  EXPECT_LT(result.peak_rss_kb, kSmallInputPeakKb) << result.err;
}

}  // namespace lfsp::testing
