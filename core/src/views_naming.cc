#include "lfsp/core/views_naming.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <regex>
#include <set>

#include "lfsp/core/error.h"
#include "lfsp/core/hci_config.h"
#include "views_folder_internal.h"

namespace lfsp {
namespace fs = std::filesystem;

namespace {

const char* const kImageExtensions = "png|PNG|tif|tiff|TIF|TIFF|exr|EXR|jpg|jpeg|JPG|JPEG|bmp|BMP";
// View indices have at most this many digits (so std::stol cannot overflow); longer numbers are not indices.
// Patterns below write it as {1,6}.

// input_CamNNN.<ext> files of the folder, by camera number.
std::map<int, fs::path> FindHciFiles(const fs::path& folder, const char* prefix) {
  static const std::regex kPattern(std::string("_Cam([0-9]{3,4})\\.(") + kImageExtensions + ")");
  std::map<int, fs::path> views;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    std::smatch match;
    const std::string rest = name.substr(std::string(prefix).size());
    if (!std::regex_match(rest, match, kPattern)) continue;
    const int camera = std::stoi(match[1].str());
    if (views.count(camera)) ThrowFileError(entry.path().string(), "two files for camera " + match[1].str());
    views[camera] = entry.path();
  }
  return views;
}

// HCI angular size: parameters.cfg's num_cams_x/num_cams_y, else the square root of the view count.
std::pair<int, int> HciAngularSize(const fs::path& folder, std::size_t view_count) {
  std::error_code ec;
  const fs::path config = folder / internal::kConfigName;
  if (fs::exists(config, ec)) {
    const Metadata metadata = ReadHciConfig(config);
    if (metadata.contains("extrinsics")) {
      const Metadata& extrinsics = metadata["extrinsics"];
      // A declared angular size that is not a count is garbage, not an absent one: refuse rather than guess.
      for (const char* key : {"num_cams_x", "num_cams_y"})
        if (extrinsics.contains(key) && !extrinsics[key].is_number_integer())
          ThrowFileError(config.string(), std::string(key) + " = " + extrinsics[key].dump() + " is not a whole number");
      if (extrinsics.contains("num_cams_x") && extrinsics.contains("num_cams_y") &&
          extrinsics["num_cams_x"].is_number_integer() && extrinsics["num_cams_y"].is_number_integer()) {
        // Read wide: 4294967303 must not wrap to 7.
        const long long nu = extrinsics["num_cams_x"].get<long long>();
        const long long nv = extrinsics["num_cams_y"].get<long long>();
        if (nu <= 0 || nv <= 0 || nu > 64 || nv > 64)
          ThrowFileError(config.string(), "num_cams_x/num_cams_y out of range");
        return {static_cast<int>(nu), static_cast<int>(nv)};
      }
    }
  }
  const int side = static_cast<int>(std::lround(std::sqrt(static_cast<double>(view_count))));
  if (static_cast<std::size_t>(side * side) != view_count)
    ThrowFileError(folder.string(), std::to_string(view_count) +
                                        " views do not form a square grid and parameters.cfg gives no num_cams_x/y");
  return {side, side};
}

ViewsLayout HciLayout(const fs::path& folder, const std::map<int, fs::path>& files) {
  const auto [nu, nv] = HciAngularSize(folder, files.size());
  const int view_count = nu * nv;
  for (int camera = 0; camera < view_count; ++camera)
    if (!files.count(camera))
      ThrowFileError((folder / internal::HciViewFileName("input", camera, ".png")).string(),
                     "missing view " + std::to_string(camera) + " of " + std::to_string(view_count));
  if (static_cast<int>(files.size()) != view_count)
    ThrowFileError(folder.string(), "found " + std::to_string(files.size()) + " views, expected " +
                                        std::to_string(view_count) + " (" + std::to_string(nu) + "x" +
                                        std::to_string(nv) + ")");
  ViewsLayout layout;
  layout.naming = "HCI input_Cam###";
  layout.nu = nu;
  layout.nv = nv;
  for (const auto& [camera, path] : files) layout.files.push_back(path);
  // weight_CamNNN holds the ray weights of input_CamNNN. Only their number used to be compared, so weights numbered
  // from 1 beside views numbered from 0 gave every view the next camera's weights; they are paired by camera
  // number, and weights that do not cover exactly the views' cameras are refused (no weight files: no weights).
  const std::map<int, fs::path> weights = FindHciFiles(folder, "weight");
  if (!weights.empty()) {
    for (int camera = 0; camera < view_count; ++camera)
      if (!weights.count(camera))
        ThrowFileError(folder.string(), "weight files do not match the views: " + files.at(camera).filename().string() +
                                            " has no " + internal::HciViewFileName("weight", camera, "") +
                                            " (weights pair with views by camera number)");
    for (const auto& [camera, path] : weights)  // every camera of a view has its weight: the rest have no view
      if (camera >= view_count)
        ThrowFileError(folder.string(), "weight files do not match the views: " + path.filename().string() +
                                            " has no view (the views are " + internal::HciViewFileName("input", 0, "") +
                                            ".." + internal::HciViewFileName("input", view_count - 1, "") + ")");
    for (int camera = 0; camera < view_count; ++camera) layout.weight_files.push_back(weights.at(camera));
  }
  layout.description = "HCI naming input_Cam000.. (camera = row x " + std::to_string(nu) + " + column), " +
                       std::to_string(nu) + "x" + std::to_string(nv) + " views";
  return layout;
}

// One file's (row, column) as its name gives them.
struct NamedView {
  fs::path path;
  long row = 0;
  long column = 0;
};

// Views from names with (row, column) read by `read` (nullopt: not a view), indices shifted so the smallest is 0.
template <typename Read>
std::optional<ViewsLayout> GridLayout(const fs::path& folder, const std::string& naming, Read read) {
  // Files are grouped by what precedes the numbers; the largest group is the views (view_1_1.png beside
  // depth_1_1.png), and two groups of the same size are ambiguous.
  std::map<std::string, std::vector<NamedView>> groups;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    std::string prefix;
    if (std::optional<NamedView> view = read(entry.path(), prefix)) groups[prefix].push_back(*view);
  }
  if (groups.empty()) return std::nullopt;
  const auto largest = std::max_element(groups.begin(), groups.end(),
                                        [](const auto& a, const auto& b) { return a.second.size() < b.second.size(); });
  for (const auto& [prefix, members] : groups)
    if (prefix != largest->first && members.size() == largest->second.size())
      ThrowFileError(folder.string(), naming + " naming: two families of views, '" + largest->first + "...' and '" +
                                          prefix + "...'; choose one with " + OptionName("views_pattern"));
  const std::vector<NamedView>& views = largest->second;
  const std::string prefix = largest->first;
  if (views.size() < 2) return std::nullopt;
  std::set<long> rows, columns;
  for (const NamedView& v : views) {
    rows.insert(v.row);
    columns.insert(v.column);
  }
  const long nu = static_cast<long>(columns.size()), nv = static_cast<long>(rows.size());
  const long row0 = *rows.begin(), column0 = *columns.begin();
  if (*rows.rbegin() - row0 + 1 != nv || *columns.rbegin() - column0 + 1 != nu || nu > 64 || nv > 64)
    return std::nullopt;  // gaps in the numbering or implausibly many: not this layout
  ViewsLayout layout;
  layout.naming = naming;
  layout.nu = static_cast<int>(nu);
  layout.nv = static_cast<int>(nv);
  layout.files.assign(static_cast<std::size_t>(nu * nv), fs::path());
  for (const NamedView& v : views) {
    fs::path& slot = layout.files[static_cast<std::size_t>((v.row - row0) * nu + (v.column - column0))];
    if (!slot.empty()) ThrowFileError(v.path.string(), "names the same view as " + slot.filename().string());
    slot = v.path;
  }
  for (long r = 0; r < nv; ++r)
    for (long c = 0; c < nu; ++c)
      if (layout.files[static_cast<std::size_t>(r * nu + c)].empty())
        ThrowFileError(folder.string(), naming + " naming: no file for row " + std::to_string(r + row0) + ", column " +
                                            std::to_string(c + column0));
  layout.description = naming + " naming (prefix '" + prefix + "'), rows " + std::to_string(row0) + ".." +
                       std::to_string(*rows.rbegin()) + " and columns " + std::to_string(column0) + ".." +
                       std::to_string(*columns.rbegin()) + " as views 0..: " + std::to_string(nu) + "x" +
                       std::to_string(nv) + " views";
  return layout;
}

// A pattern such as 'view_{row}_{col}.png' as a regex capturing row and column (in that order of appearance).
struct CompiledPattern {
  std::regex regex;
  int row_group = 0;
  int column_group = 0;
};

CompiledPattern CompilePattern(const std::string& pattern) {
  std::string regex;
  int group = 0;
  CompiledPattern compiled;
  for (std::size_t i = 0; i < pattern.size();) {
    if (pattern.compare(i, 5, "{row}") == 0) {
      regex += "([0-9]{1,6})";
      compiled.row_group = ++group;
      i += 5;
    } else if (pattern.compare(i, 5, "{col}") == 0) {
      regex += "([0-9]{1,6})";
      compiled.column_group = ++group;
      i += 5;
    } else if (pattern.compare(i, 7, "{index}") == 0) {
      regex += "[0-9]+";  // ignored, so any length
      i += 7;
    } else {
      const char c = pattern[i++];
      if (std::string("\\^$.|?*+()[]{}").find(c) != std::string::npos) regex += '\\';
      regex += c;
    }
  }
  if (compiled.row_group == 0 || compiled.column_group == 0)
    throw Error(OptionName("views_pattern") + " '" + pattern + "': needs both {row} and {col}, e.g. '{row}_{col}.png'");
  compiled.regex = std::regex(regex);
  return compiled;
}

}  // namespace

namespace internal {

std::string HciViewFileName(const char* prefix, int camera, const std::string& extension) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_Cam%03d%s", prefix, camera, extension.c_str());
  return name;
}

}  // namespace internal

ViewsLayout FindViewsLayout(const fs::path& folder, const std::string& pattern) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) ThrowFileError(folder.string(), "not a folder of views");
  std::optional<ViewsLayout> layout;
  if (!pattern.empty()) {
    const CompiledPattern compiled = CompilePattern(pattern);
    layout = GridLayout(
        folder, OptionName("views_pattern") + " '" + pattern + "'", [&](const fs::path& path, std::string& prefix) {
          std::smatch match;
          const std::string name = path.filename().string();
          if (!std::regex_match(name, match, compiled.regex)) return std::optional<NamedView>();
          prefix.clear();
          return std::optional<NamedView>(
              {path, std::stol(match[compiled.row_group].str()), std::stol(match[compiled.column_group].str())});
        });
    if (!layout)
      ThrowFileError(folder.string(),
                     "no files match " + OptionName("views_pattern") + " '" + pattern + "' as a grid of views");
    return *layout;
  }
  if (const std::map<int, fs::path> hci = FindHciFiles(folder, "input"); !hci.empty()) return HciLayout(folder, hci);

  // LFToolbox: <name>_<index>_<a>_<b>, where the index numbers the views 1..N; a is the column.
  static const std::regex kThreeNumbers(std::string("(.*)_([0-9]{1,6})_([0-9]{1,6})_([0-9]{1,6})\\.(") +
                                        kImageExtensions + ")");
  std::set<long> indices;
  layout = GridLayout(folder, "LFToolbox <index>_<column>_<row>", [&](const fs::path& path, std::string& prefix) {
    std::smatch match;
    const std::string name = path.filename().string();
    if (!std::regex_match(name, match, kThreeNumbers)) return std::optional<NamedView>();
    prefix = match[1].str();
    indices.insert(std::stol(match[2].str()));
    return std::optional<NamedView>({path, std::stol(match[4].str()), std::stol(match[3].str())});
  });
  const bool indexed = layout && static_cast<int>(indices.size()) == layout->nu * layout->nv && *indices.begin() == 1 &&
                       *indices.rbegin() == layout->nu * layout->nv;
  if (layout && indexed) return *layout;

  // [prefix]<row>_<col>: the first number is the row.
  static const std::regex kTwoNumbers(std::string("(.*?)([0-9]{1,6})_([0-9]{1,6})\\.(") + kImageExtensions + ")");
  layout = GridLayout(folder, "<row>_<col>", [&](const fs::path& path, std::string& prefix) {
    std::smatch match;
    const std::string name = path.filename().string();
    if (!std::regex_match(name, match, kTwoNumbers)) return std::optional<NamedView>();
    prefix = match[1].str();
    return std::optional<NamedView>({path, std::stol(match[2].str()), std::stol(match[3].str())});
  });
  if (layout) return *layout;
  ThrowFileError(folder.string(),
                 "folder holds no light-field views: expected HCI input_Cam000.png.., <row>_<col>.png (any prefix), "
                 "LFToolbox <name>_<index>_<a>_<b>.png, or name the files with " +
                     OptionName("views_pattern") + " '{row}_{col}.png'");
}

}  // namespace lfsp
