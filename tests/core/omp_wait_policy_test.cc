// The executables' default OpenMP wait policy (core/startup/omp_wait_policy.cc, issue 48): libgomp inside `lfsp`
// must spin for zero rounds unless the user chose otherwise. libgomp prints the spin count it settled on when
// OMP_DISPLAY_ENV=verbose, which is what these tests read: a wrong mechanism (one that sets the variable too late for
// libgomp's initialiser) leaves it at libgomp's own 300000.

#include <gtest/gtest.h>

#include <cstdlib>
#include <regex>
#include <string>

#include "test_support.h"

namespace lfsp::testing {
namespace {

// The spin count libgomp reports in `lfsp --version` with the given variables set ("" unsets one).
std::string SpinCountOfLfsp(const std::string& wait_policy, const std::string& spin_count) {
  const auto set = [](const char* name, const std::string& value) {
    if (value.empty())
      unsetenv(name);
    else
      setenv(name, value.c_str(), 1);
  };
  set("OMP_WAIT_POLICY", wait_policy);
  set("GOMP_SPINCOUNT", spin_count);
  setenv("OMP_DISPLAY_ENV", "verbose", 1);
  const CommandResult result = RunLfsp({"--version"});
  unsetenv("OMP_DISPLAY_ENV");
  unsetenv("OMP_WAIT_POLICY");
  unsetenv("GOMP_SPINCOUNT");
  EXPECT_EQ(result.exit_status, 0) << result.err;
  std::smatch match;
  const std::string displayed = result.out + result.err;
  if (!std::regex_search(displayed, match, std::regex("GOMP_SPINCOUNT = '([0-9]+)'"))) return "not displayed";
  return match[1];
}

TEST(OmpWaitPolicy, LfspWaitsPassivelyByDefault) { EXPECT_EQ(SpinCountOfLfsp("", ""), "0"); }

TEST(OmpWaitPolicy, TheUsersWaitPolicyWins) {
  EXPECT_EQ(SpinCountOfLfsp("active", ""), "30000000000");
  EXPECT_EQ(SpinCountOfLfsp("passive", ""), "0");
}

TEST(OmpWaitPolicy, TheUsersSpinCountWins) { EXPECT_EQ(SpinCountOfLfsp("", "12345"), "12345"); }

TEST(OmpWaitPolicy, OtherVariablesReadAsSet) {
  setenv("LFSP_WAIT_POLICY_TEST", "value=with=equals", 1);
  ASSERT_NE(std::getenv("LFSP_WAIT_POLICY_TEST"), nullptr);
  EXPECT_STREQ(std::getenv("LFSP_WAIT_POLICY_TEST"), "value=with=equals");
  EXPECT_EQ(std::getenv("LFSP_WAIT_POLICY_TEST_NOT_SET"), nullptr);
  EXPECT_EQ(std::getenv("LFSP_WAIT_POLICY"), nullptr);  // a prefix of a set name is not that name
  EXPECT_EQ(std::getenv(""), nullptr);
  unsetenv("LFSP_WAIT_POLICY_TEST");
  // This test executable has the same default: it is linked like `lfsp`.
  unsetenv("OMP_WAIT_POLICY");
  unsetenv("GOMP_SPINCOUNT");
  ASSERT_NE(std::getenv("OMP_WAIT_POLICY"), nullptr);
  EXPECT_STREQ(std::getenv("OMP_WAIT_POLICY"), "passive");
}

}  // namespace
}  // namespace lfsp::testing
