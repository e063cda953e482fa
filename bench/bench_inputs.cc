// What several bench files share: running the `lfsp` executable, the full-size simulated captures it makes, and
// reading and printing the figures of its summaries.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "bench_case.h"

namespace lfsp::bench {

namespace fs = std::filesystem;

nlohmann::json ReadJson(const fs::path& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

std::string Fixed(double value, int decimals) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

void RunLfspBinary(const std::string& binary, const std::string& arguments, const std::string& environment) {
  const std::string command = environment + binary + " -q " + arguments + " > /dev/null";
  if (std::system(command.c_str()) != 0) throw std::runtime_error("failed: " + command);
}

void RunLfsp(const std::string& arguments, const std::string& environment) {
  RunLfspBinary(LFSP_BINARY_PATH, arguments, environment);
}

std::string ReferenceLfsp() {
  const char* configured = std::getenv("LFSP_BENCH_REFERENCE");
  const std::string path = configured && *configured ? configured : LFSP_REFERENCE_BINARY;
  std::error_code ec;
  return fs::is_regular_file(path, ec) ? path : "";
}

fs::path FullSizeCapture(const std::string& camera, const std::string& scene) {
  std::string folder_scene = scene;
  std::replace(folder_scene.begin(), folder_scene.end(), '-', '_');  // a scene name as part of a file name
  const fs::path folder = fs::temp_directory_path() / ("lfsp_bench_" + folder_scene + "_" + camera);
  const fs::path capture = folder / (camera == "illum" ? "capture.LFR" : "capture.lfp");
  if (!fs::exists(capture) || !fs::exists(folder / "ground_truth" / "decoded.h5"))
    RunLfsp("simulate --camera " + camera + " --scene " + scene + " --out " + folder.string());
  return capture;
}

}  // namespace lfsp::bench
