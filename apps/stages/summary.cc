#include "stages/summary.h"

#include <fstream>
#include <string>

#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/version.h"

namespace lfsp::stages {
namespace {

void WriteText(const std::string& text, const std::filesystem::path& path) {
  AtomicOutput output(path);
  {
    std::ofstream file(output.temporary());
    if (!file) ThrowFileError(path.string(), "cannot create");
    file << text << "\n";
    if (!file.flush()) ThrowFileError(path.string(), "write failed");
  }
  output.Commit();
}

// The summary with lfsp's version first ("version": the same string as `lfsp --version`); a JSON that is not an
// object (OUT.planes.json, a list) is written as it is.
template <typename Json>
Json WithVersion(const Json& summary) {
  if (!summary.is_object()) return summary;
  Json out = Json::object();
  out["version"] = Version();
  for (const auto& [key, value] : summary.items())
    if (key != "version") out[key] = value;
  return out;
}

}  // namespace

void WriteJsonSummary(const nlohmann::json& summary, const std::filesystem::path& path) {
  WriteText(WithVersion(summary).dump(2), path);
}

void WriteJsonSummary(const nlohmann::ordered_json& summary, const std::filesystem::path& path) {
  WriteText(WithVersion(summary).dump(2), path);
}

std::filesystem::path SummaryPathFor(const std::filesystem::path& output) {
  std::error_code ec;
  if (std::filesystem::is_directory(output, ec) || !output.has_extension()) return output / "summary.json";
  std::filesystem::path path = output;
  path.replace_extension(".summary.json");
  return path;
}

}  // namespace lfsp::stages
