// Long commands show progress on a terminal and stay quiet otherwise (issue 15, item 13): each command runs with its
// stderr on a pseudo-terminal, whose output must hold the command's progress bar, and through a pipe, whose must not.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lfsp/core/hdf5_bundle.h"
#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using testing::RunLfsp;
using testing::TempDir;

TEST(Progress, DrawnOnATerminalOnly) {
  TempDir temp;
  Bundle bundle;
  bundle.light_field = LightField({5, 5, 64, 48, 3});
  for (std::size_t i = 0; i < bundle.light_field.size(); ++i)
    bundle.light_field.data()[i] = static_cast<float>((i * 2654435761u) % 1000) / 1000.0f;
  bundle.disparity = DisparityMap(64, 48, 0.0f);
  bundle.labels = Labels(bundle.light_field.shape(), 0);
  WriteBundle(bundle, temp / "lf.h5");
  const fs::path sample = testing::SourceDir() / "samples" / "mini-illum" / "capture.LFR";
  const std::string lf = (temp / "lf.h5").string();
  const std::vector<std::pair<std::string, std::vector<std::string>>> commands = {
      {"depth [", {"depth", lf, "--dmin", "-1", "--dmax", "1", "--out", (temp / "d.pfm").string()}},
      {"segment [", {"segment", lf, "--out", (temp / "s.h5").string()}},
      {"evaluate [", {"evaluate", "segmentation", lf, "--baselines"}},
      {"decode [", {"decode", sample.string(), "--out", (temp / "dec.h5").string()}},
  };
  for (const auto& [bar, arguments] : commands) {
    SCOPED_TRACE(arguments.front());
    const std::string terminal = testing::RunLfspWithStderrOnTerminal(arguments);
    EXPECT_NE(terminal.find(bar), std::string::npos) << terminal;
    EXPECT_NE(terminal.find("100%"), std::string::npos) << terminal;
    const testing::CommandResult piped = RunLfsp(arguments);
    EXPECT_EQ(piped.exit_status, 0) << piped.err;
    EXPECT_EQ(piped.err.find(bar), std::string::npos) << piped.err;
    EXPECT_EQ(piped.err.find('\r'), std::string::npos) << piped.err;
  }
}

}  // namespace
}  // namespace lfsp
