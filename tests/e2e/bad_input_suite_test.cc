// The bad-input suite (issue 15): every file format lfsp parses, broken in the ways files break (empty, truncated,
// header overwritten, the wrong kind of file under the right name, a part missing), given to every command that
// reads it. Each case must exit 2 with exactly one line `lfsp: error: ...` naming the file, stay under 1 GiB of
// memory (every input here is under 1 MB) and leave nothing where its output was to go.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::ReadBytes;
using testing::RunLfsp;
using testing::SourceDir;
using testing::TempDir;
using testing::WriteBytes;

constexpr long kPeakBoundKb = 1024L * 1024L;  // 1 GiB for inputs under 1 MB

// How a good file is broken. Each returns the broken bytes (or makes the broken folder).
struct Breakage {
  std::string name;
  std::function<std::string(const std::string& good)> bytes;
};

std::vector<Breakage> FileBreakages() {
  return {
      {"empty", [](const std::string&) { return std::string(); }},
      {"first-16-bytes", [](const std::string& good) { return good.substr(0, 16); }},
      {"truncated-half", [](const std::string& good) { return good.substr(0, good.size() / 2); }},
      {"truncated-90pc", [](const std::string& good) { return good.substr(0, good.size() * 9 / 10); }},
      {"header-garbage",
       [](const std::string& good) {
         std::string bad = good;
         for (std::size_t i = 0; i < std::min<std::size_t>(256, bad.size()); ++i)
           bad[i] = static_cast<char>((i * 97 + 13) & 0xff);
         return bad;
       }},
  };
}

// One command reading one input: the arguments with INPUT and OUT (a path inside the case's own output folder)
// still to be filled in.
struct Reader {
  std::string name;
  std::vector<std::string> arguments;
};

struct Case {
  std::string name;
  std::vector<std::string> arguments;
  fs::path culprit;  // what the message must name
  fs::path out_dir;  // must be empty afterwards
};

std::vector<std::string> Filled(const std::vector<std::string>& pattern, const fs::path& input, const fs::path& out,
                                const fs::path& seeds) {
  std::vector<std::string> arguments;
  for (const std::string& part : pattern) {
    if (part == "INPUT")
      arguments.push_back(input.string());
    else if (part.rfind("OUT", 0) == 0)
      arguments.push_back((out / ("result" + part.substr(3))).string());
    else if (part.rfind("SEED:", 0) == 0)
      arguments.push_back((seeds / part.substr(5)).string());
    else
      arguments.push_back(part);
  }
  return arguments;
}

// The good files every breakage starts from, made by the CLI itself from the bundled samples.
class BadInputSuite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    seeds_ = new TempDir();
    const fs::path ideal = SourceDir() / "samples" / "ideal" / "ideal.h5";
    fs::copy_file(ideal, Seed("lf.h5"));
    for (const char* target : {"lf.png", "lf.mat", "disparity.pfm", "views"})
      ASSERT_EQ(RunLfsp({"convert", ideal.string(), Seed(target).string()}).exit_status, 0) << target;
    const fs::path mini = SourceDir() / "samples" / "mini-illum";
    fs::copy_file(mini / "capture.LFR", Seed("capture.LFR"));
    fs::copy(mini / "whites", Seed("whites"));
    fs::copy_file(SourceDir() / "samples" / "ideal" / "scene.json", Seed("scene.json"));
  }
  static void TearDownTestSuite() { delete seeds_; }
  static fs::path Seed(const std::string& name) { return seeds_->path() / name; }

  // The cases of one input file: every breakage of it, given to every reader.
  void AddFileCases(const std::string& seed, const std::vector<Reader>& readers, const fs::path& work) {
    const std::string good = ReadBytes(Seed(seed));
    for (const Breakage& breakage : FileBreakages()) {
      const fs::path folder = work / (seed + "." + breakage.name);
      fs::create_directories(folder);
      const fs::path input = folder / seed;
      WriteBytes(input, breakage.bytes(good));
      for (const Reader& reader : readers)
        AddCase(seed + "/" + breakage.name + "/" + reader.name, reader, input, input);
    }
  }

  // The cases of a views folder broken in one view (or its parameters), given to every reader.
  void AddViewsFolderCases(const std::vector<Reader>& readers, const fs::path& work) {
    struct FolderBreakage {
      std::string name;
      std::string file;  // the file broken, in the folder
      std::function<void(const fs::path&)> apply;
    };
    const std::vector<FolderBreakage> breakages = {
        {"view-truncated", "input_Cam024.png",
         [](const fs::path& p) { WriteBytes(p, ReadBytes(p).substr(0, ReadBytes(p).size() / 2)); }},
        {"view-empty", "input_Cam024.png", [](const fs::path& p) { WriteBytes(p, ""); }},
        {"view-missing", "input_Cam024.png", [](const fs::path& p) { fs::remove(p); }},
        {"view-not-an-image", "input_Cam003.png", [](const fs::path& p) { WriteBytes(p, "not a PNG at all\n"); }},
        {"view-another-size", "input_Cam010.png",
         [this](const fs::path& p) { fs::copy_file(Seed("lf.png"), p, fs::copy_options::overwrite_existing); }},
        {"parameters-garbage", "parameters.cfg",
         [](const fs::path& p) { WriteBytes(p, "[extrinsics]\nnum_cams_x = lots\nnum_cams_y = 7\n"); }},
        {"parameters-wrong-count", "parameters.cfg",
         [](const fs::path& p) { WriteBytes(p, "[extrinsics]\nnum_cams_x = 5\nnum_cams_y = 7\n"); }},
    };
    for (const FolderBreakage& breakage : breakages) {
      const fs::path folder = work / ("views." + breakage.name) / "views";
      fs::create_directories(folder.parent_path());
      fs::copy(Seed("views"), folder, fs::copy_options::recursive);
      breakage.apply(folder / breakage.file);
      for (const Reader& reader : readers)
        AddCase("views/" + breakage.name + "/" + reader.name, reader, folder, folder);
    }
  }

  void AddCase(const std::string& name, const Reader& reader, const fs::path& input, const fs::path& culprit) {
    const fs::path out = input.parent_path() / ("out." + reader.name);
    fs::create_directories(out);
    cases_.push_back({name, Filled(reader.arguments, input, out, seeds_->path()), culprit, out});
  }

  static TempDir* seeds_;
  std::vector<Case> cases_;
};

TempDir* BadInputSuite::seeds_ = nullptr;

// Every command that reads a light field.
std::vector<Reader> LightFieldReaders() {
  return {
      {"info", {"info", "INPUT"}},
      {"depth", {"depth", "INPUT", "--dmin", "-1", "--dmax", "1", "--out", "OUT.pfm"}},
      {"segment", {"segment", "INPUT", "--disparity", "SEED:disparity.pfm", "--out", "OUT.h5"}},
      {"convert", {"convert", "INPUT", "OUT.h5"}},
      {"refocus", {"refocus", "INPUT", "--disparities", "0.5", "--out", "OUT"}},
      {"recolor", {"recolor", "INPUT", "--labels", "SEED:lf.h5", "--label-ids", "1", "--hue", "30", "--out", "OUT.h5"}},
      {"pipeline", {"pipeline", "INPUT", "--out", "OUT"}},
  };
}

void ExpectRefusedCleanly(const Case& c, const CommandResult& result) {
  SCOPED_TRACE(c.name);
  EXPECT_EQ(result.exit_status, 2) << result.err << result.out;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_EQ(result.err.rfind("lfsp: error: ", 0), 0u) << result.err;
  EXPECT_NE(result.err.find(c.culprit.string()), std::string::npos)
      << "'" << result.err << "' does not name " << c.culprit;
  EXPECT_LT(result.peak_rss_kb, kPeakBoundKb);
  EXPECT_TRUE(fs::is_empty(c.out_dir)) << "left behind: " << fs::directory_iterator(c.out_dir)->path();
}

TEST_F(BadInputSuite, EveryParserAndEveryCommandRefusesBrokenFilesInOneLine) {
  const TempDir work;
  for (const char* seed : {"lf.h5", "lf.png", "lf.mat"}) AddFileCases(seed, LightFieldReaders(), work.path());
  AddViewsFolderCases(LightFieldReaders(), work.path());
  AddFileCases(
      "disparity.pfm",
      {{"segment", {"segment", "SEED:lf.h5", "--disparity", "INPUT", "--out", "OUT.h5"}},
       {"evaluate-depth", {"evaluate", "depth", "INPUT", "--gt", "SEED:disparity.pfm"}},
       {"refocus-all-in-focus", {"refocus", "SEED:lf.h5", "--all-in-focus", "--disparity", "INPUT", "--out", "OUT"}}},
      work.path());
  AddFileCases("capture.LFR",
               {{"info", {"info", "INPUT"}},
                {"grid", {"grid", "INPUT", "--out", "OUT.json"}},
                {"decode", {"decode", "INPUT", "--white-images", "SEED:whites", "--out", "OUT.h5"}}},
               work.path());
  AddFileCases("scene.json", {{"simulate", {"simulate", "--scene", "INPUT", "--ideal-only", "--out", "OUT"}}},
               work.path());

  ASSERT_GE(cases_.size(), 100u);  // the floor
  for (const Case& c : cases_) ExpectRefusedCleanly(c, RunLfsp(c.arguments));
  std::printf("%zu bad-input cases\n", cases_.size());
}

}  // namespace
}  // namespace lfsp
