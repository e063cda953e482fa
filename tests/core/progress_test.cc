// Progress: observers see every tick; a requested cancellation stops the loop at its next tick.

#include "lfsp/core/progress.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace lfsp {
namespace {

struct ObserverReset {
  ~ObserverReset() {
    Progress::SetObserver({});
    ClearCancellation();
  }
};

TEST(Progress, ObserverSeesEveryTickWithItsLabelAndTotal) {
  const ObserverReset reset;
  std::vector<std::string> seen;
  Progress::SetObserver([&](const std::string& label, std::size_t done, std::size_t total) {
    seen.push_back(label + " " + std::to_string(done) + "/" + std::to_string(total));
  });
  Progress progress("work", 3);
  progress.Tick();
  progress.Tick(2);
  EXPECT_EQ(seen, (std::vector<std::string>{"work 1/3", "work 3/3"}));
}

TEST(Progress, CancellationStopsTheLoopAtItsNextTick) {
  const ObserverReset reset;
  int steps_run = 0;
  const auto long_loop = [&] {
    Progress progress("loop", 100);
    for (int step = 0; step < 100; ++step) {
      ++steps_run;
      if (step == 4) RequestCancellation();  // as Ctrl-C would, from a signal handler
      progress.Tick();
    }
  };
  EXPECT_THROW(long_loop(), Cancelled);
  EXPECT_EQ(steps_run, 5);
  EXPECT_TRUE(CancellationRequested());
  ClearCancellation();
  steps_run = 0;
  EXPECT_NO_THROW([&] {
    Progress progress("again", 3);
    for (int step = 0; step < 3; ++step, ++steps_run) progress.Tick();
  }());
  EXPECT_EQ(steps_run, 3);
}

TEST(Progress, AnObserversExceptionReachesTheCaller) {
  const ObserverReset reset;
  Progress::SetObserver([](const std::string&, std::size_t, std::size_t) { throw std::runtime_error("stop"); });
  Progress progress("work", 2);
  EXPECT_THROW(progress.Tick(), std::runtime_error);
}

}  // namespace
}  // namespace lfsp
